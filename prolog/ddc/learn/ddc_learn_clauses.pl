/*  ddc_learn_clauses.pl -- the learned clauses: a leaf's clause (the path
    from the root, the leaf's statistical model) and a target's whole tree
    as one clause of nested if-then-else goals.
*/

:- module(ddc_learn_clauses,
          [ learn_clause/5,             % +Data, +Node, +Model, +Regressors, -Clause
            learn_leaf_text/5,          % +Data, +Node, +ModelText, +Regressors, -Texts
            learn_background_for/3,     % +Data, +Leaves, -Texts
            learn_tree_text/3,          % +Data, +Leaves, -Text
            learn_root_model/3          % +Data, +Target, +ModelText
          ]).

:- use_module(library(lists)).
:- use_module(library(apply)).
:- use_module(library(error)).
:- use_module(library(pairs)).
:- use_module(ddc_learn_data).
:- use_module(ddc_learn_records).
:- use_module('../lang/ddc_body', [conj_from_list/2]).
:- use_module(ddc_learn_text, [clause_names/3, learn_clause_text/3, new_var/4, print_conj/1,
                               print_literal/1, print_dc_term/1, term_text/3]).
:- use_module(ddc_learn_candidates, [agg_call/4, branch_count/2, fresh_values/2,
                                     node_branch_literal/8]).
:- use_module(ddc_learn_background, [learn_background/3]).

:- set_prolog_flag(optimise, true).

/** <module> Learned clauses

A leaf's clause is the target's head, the literals of the path from the
root (each step's branch, node_branch_literal/8) and the leaf's model: its
distribution and, for a model with regressors, the goals that compute the
distribution's parameters from the path's values.  The tree form says
the same program as one clause per target (learn_tree_text/3).
*/

                 /*******************************
                 *            CLAUSES           *
                 *******************************/

%!  learn_clause(+Data, +Node, +Model, +Regressors:list(integer), -Clause) is det.
%
%   The clause of a leaf: the target's head, the literals of the path from
%   the root to Node (its branch at each step), and Model's statistical
%   model and distribution.  Regressors are the path steps (from 0) whose
%   values are the model's inputs, in order.  Model is one of
%   finite(Probs), gaussian(Mean, Var), linear_gaussian(Weights, Var),
%   logistic(Weights) (the probability of the domain's first value),
%   softmax(WeightRows), poisson(Rate), poisson_log_linear(Weights);
%   weights are [w1, ..., wn, b].  Clause is clause(Term, Bindings) for
%   learn_clause_text/3.
learn_clause(M, Node, Model, Regs, Clause) :-
    leaf_clause(M, Node, Model, Regs, Clause, _, _).

%!  learn_leaf_text(+Data, +Node, +ModelText, +Regressors, -Texts:dict) is det.
%
%   learn_clause/5 for Python: the model as Prolog text; Texts has clause
%   (the clause in DC syntax), distribution (its head's) and model (the
%   statistical model's goals, "" without regressors; a root model's
%   features and scores left out).
learn_leaf_text(M, Node, ModelText, Regs, _{clause: CT, distribution: DT, model: MT}) :-
    term_string(Model, ModelText),
    leaf_clause(M, Node, Model, Regs, Clause, Dist, Goals),
    Clause = clause(_, Bs),
    learn_clause_text(M, Clause, CT),
    term_text(Dist, Bs, DT),
    (   Goals == [] -> MT = ""
    ;   conj_from_list(Goals, GC), term_text(GC, Bs, MT0), strip_parens(MT0, MT)
    ).

%   leaf_clause(+M, +Node, +Model, +Regs, -Clause, -Dist, -Goals): the
%   leaf's clause(Term, Bindings) (learn_clause/5), its head's distribution
%   and its model's goals (not those of a root model's features and
%   scores, which the clause computes before them).
leaf_clause(M, Node, Model, Regs, clause((Head ~ Dist := Body), Bs), Dist, Goals) :-
    clause_parts(M, Node, Model, Regs, Head, Dist, Lits, SGoals-Goals, Bs),
    append([Lits, SGoals, Goals], Ls),
    conj_from_list(Ls, Body).

strip_parens(S0, S) :-
    (   sub_string(S0, 0, 1, _, "("), sub_string(S0, _, 1, 0, ")")
    ->  sub_string(S0, 1, _, 1, S)
    ;   S = S0
    ).

%!  learn_background_for(+Data, +Leaves:list, -Texts:list(string)) is det.
%
%   learn_background/3 for the clauses of Leaves, each [Node, ModelText,
%   Regressors].
learn_background_for(M, Leaves, Texts) :-
    findall(C, ( member([Node, MT, Regs], Leaves), term_string(Model, MT),
                 learn_clause(M, Node, Model, Regs, C) ), Cs),
    learn_background(M, Cs, Texts).

%!  learn_root_model(+Data, +Target:atom, +ModelText:string) is det.
%
%   Set the root model of Target (its internal name) that the leaves'
%   negative regressors read: ModelText is the text of
%   root_model(Features, Rows).  Features are the model's inputs, each
%   value(CandidateId, Fill) (a numeric candidate's value, Fill where it is
%   undefined; a count) or branch(CandidateId, Branch) (1 where the
%   branch's literal holds, else 0) of a candidate that reads only the
%   head's variables; Rows are the weights [w1, ..., wn, b] of each score,
%   the linear predictor z_J = w.x + b over the features.
learn_root_model(M, N, Text) :-
    term_string(T, Text),
    (   T = root_model(Fs, Rows), is_list(Fs), is_list(Rows) -> true
    ;   type_error(root_model, T)
    ),
    retractall(M:'$ddcl_root_model'(N, _)),
    assertz(M:'$ddcl_root_model'(N, T)).

%!  learn_tree_text(+Data, +Leaves:list, -Text:string) is semidet.
%
%   A target's whole tree as one DC clause (its decision-tree form): the
%   head, the examples' goal, then the tree's tests as nested if-then-else
%   goals, each leaf binding the head's distribution parameters (its
%   statistical model's goals, or its constants), with a comment line of
%   Leaves' at each leaf.  Leaves are the target's leaves from left to
%   right, each [Node, ModelText, Regressors, Comment].  It is the same
%   program as the leaves' clauses (learn_clause/5): their bodies are the
%   paths of the tree, mutually exclusive, so that a grounding takes the
%   branch whose test holds at each node; a test shared by several
%   clauses is evaluated once.  Fails if the leaves' distributions are not
%   of one family (a leaf gaussian, another poisson): no single head.
learn_tree_text(M, Leaves, Text) :-
    Leaves = [[N0, MT0|_]|_],
    M:'$ddcl_node'(N0, Info, _),
    node_info_target(Info, target(N, A, Spec)),
    tree_head(M, Info, Head, HeadVars, Bs0),
    examples_guard(M, N, A, HeadVars, [], Guard),
    term_string(Model0, MT0),
    once(model_goals(Model0, Spec, _, Dist0, _, [], _)),
    dist_template(Dist0, Dist, Bs0, Bs1),
    maplist(leaf_item(M), Leaves, Items),
    start_path(HeadVars, Bs1, S0),
    tree_node(Items, tree_context(M, Spec, Dist, N-A), S0, Bs, Tree),
    dedupe_names(Bs, Bs2),
    copy_term(t(Head, Dist, Guard, Tree)-Bs2, t(H1, D1, G1, T1)-Bs3),
    maplist([Name=V]>>( var(V) -> V = '$VAR'(Name) ; true ), Bs3),
    term_variables(t(H1, D1, G1, T1), Rest),
    maplist(=('$VAR'('_')), Rest),
    with_output_to(string(Text), print_tree_clause(H1, D1, G1, T1)).

leaf_item(M, [Node, MT, Regs, Comment], Path-leaf(Model, Regs, Comment)) :-
    M:'$ddcl_node'(Node, Info, _),
    node_info_path(Info, Path),
    term_string(Model, MT).

%   dist_template(+LeafDist, -Dist, +Bs0, -Bs): the head's distribution,
%   one variable per parameter of LeafDist's family.
dist_template(finite(PVs), finite(QVs), Bs0, Bs) :-
    foldl(prob_param, PVs, QVs, 1-Bs0, _-Bs).
dist_template(gaussian(_, _), gaussian(Mean, Var), Bs0, Bs) :-
    new_var('Mean', Mean, Bs0, Bs1), new_var('Var', Var, Bs1, Bs).
dist_template(poisson(_), poisson(Rate), Bs0, Bs) :-
    new_var('Rate', Rate, Bs0, Bs).

prob_param(_:V, Q:V, I-Bs0, I1-Bs) :-
    atom_concat('P', I, Name), new_var(Name, Q, Bs0, Bs), I1 is I+1.

%   leaf_params(+LeafDist, +Dist, -Goals): a leaf's parameters as the
%   head's: a variable of its model's goals is the head's variable, a
%   constant is bound to it (P1 = 0.9).  Fails for another family.
leaf_params(finite(PVs), finite(QVs), Goals) :-
    maplist([_:V, _:W]>>(V == W), PVs, QVs),
    foldl([P:_, Q:_, G0, G]>>param_goal(P, Q, G0, G), PVs, QVs, Goals, []).
leaf_params(gaussian(Mu, V), gaussian(Mean, Var), Goals) :-
    param_goal(Mu, Mean, Goals, G1), param_goal(V, Var, G1, []).
leaf_params(poisson(R), poisson(Rate), Goals) :-
    param_goal(R, Rate, Goals, []).

param_goal(P, Q, Gs, Gs) :- var(P), !, P = Q.
param_goal(P, Q, [Q = P|Gs], Gs).

%   tree_node(+Items, +Ctx, +S, -Bs, -Tree): the (sub)tree of Items (each
%   RemainingPath-leaf(Model, Regressors, Comment)) from path state S (a
%   path_state record, see path_literal/4) in the context
%   tree_context(Data, Spec, HeadDist); Tree is leaf(Comment, Goals) or
%   node([Lit-Tree, ...]).
tree_node([[]-leaf(Model, Regs, Comment)], tree_context(M, Spec, Dist, N-A), S, Bs,
          leaf(Comment, Goals)) :- !,
    path_state_names(S, Bs0),
    path_state_regressors(S, Xs0),
    path_state_values(S, VT),
    length(HeadVars, A), append(HeadVars, _, VT),
    score_goals(M, N, HeadVars, Regs, SGoals, Xs0, Xs1, Bs0, Bs1),
    regressor_vars(Regs, Xs1, Xs),
    once(model_goals(Model, Spec, Xs, D, Goals0, Bs1, Bs)),
    leaf_params(D, Dist, Eqs),
    append([SGoals, Goals0, Eqs], Goals).
tree_node(Items, Ctx, S0, Bs, node(Branches)) :-
    Items = [[step(Id, _)|_]-_|_],
    forall(member(P-_, Items), P = [step(Id, _)|_]),
    group_branches(Items, Groups),
    tree_branches(Groups, Id, Ctx, S0, Bs, Branches0),
    Ctx = tree_context(M, _, _, _),
    (   exhaustive(M, Id, Groups)
    ->  append(Front, [_-Last], Branches0),
        (   threshold_node(Front, Last, Branches1) -> true
        ;   append(Front, [else-Last], Branches1)
        ),
        Branches = Branches1
    ;   Branches = Branches0
    ).

%   threshold_node(+Intervals, +Undefined, -Branches): the branches of a
%   threshold test read its attribute once: (K ~= V -> (V < T1 -> A ; V <
%   T2 -> B ; C) ; D).  Each interval's literal (K ~= Vi, Vi >= T0, Vi <
%   T1) has its own value variable Vi, the same value: they are unified.
threshold_node([(K ~= V, V < T)-A|Is], Undefined,
               [(K ~= V)-node([(V < T)-A|Cs]), else-Undefined]) :-
    threshold_rest(Is, V, Cs).

threshold_rest([(_ ~= V, _ >= _)-Last], V0, [else-Last]) :- !, V = V0.
threshold_rest([(_ ~= V, _ >= _, V < T)-B|Is], V0, [(V0 < T)-B|Cs]) :-
    V = V0,
    threshold_rest(Is, V0, Cs).

%   exhaustive(+M, +Id, +Groups): the branches of candidate Id that Groups
%   has cover every grounding, so that the last one is the others' else:
%   every branch of a test, of a numeric attribute (defined, undefined), of
%   thresholds (each interval, undefined), of a mean/max/min (defined,
%   empty).  A discrete attribute's are not: a value outside its domain
%   takes none.
exhaustive(M, Id, Groups) :-
    M:'$ddcl_cand'(Id, _, Spec),
    candidate_kind(Spec, Kind),
    candidate_thresholds(Spec, Ts),
    (   memberchk(Kind, [test, numeric, agg_numeric]) -> N = 2
    ;   Kind == threshold -> length(Ts, NT), N is NT+2
    ),
    length(Groups, N).

group_branches([], []).
group_branches([[step(_, B)|P]-L|Is], [B-[P-L|Ps]|Gs]) :-
    same_branch(Is, B, Ps, Rest),
    group_branches(Rest, Gs).

same_branch([[step(_, B)|P]-L|Is], B0, [P-L|Ps], Rest) :- B == B0, !,
    same_branch(Is, B0, Ps, Rest).
same_branch(Is, _, [], Is).

tree_branches([], _, _, S, Bs, []) :-
    path_state_names(S, Bs).
tree_branches([B-Sub|Gs], Id, Ctx, S0, Bs, [Lit-T|Ts]) :-
    Ctx = tree_context(M, _, _, _),
    path_literal(M, step(Id, B), S0, S1),
    path_state_literals(S1, [Lit|_]),
    tree_node(Sub, Ctx, S1, Bs1, T),
    S0 = path_state(Ls, VT, _, K, Xs),          % the next branch: S0 with Sub's names
    tree_branches(Gs, Id, Ctx, path_state(Ls, VT, Bs1, K, Xs), Bs, Ts).

%   dedupe_names(+Bs0, -Bs): the first name of each variable (a leaf's
%   model variable bound to the head's parameter keeps the head's name).
dedupe_names(Bs0, Bs) :-
    foldl([N=V, A0, A]>>( member(_=W, A0), W == V -> A = A0 ; append(A0, [N=V], A) ),
          Bs0, [], Bs).

print_tree_clause(H, D, Guard, Tree) :-
    print_literal(H), write(' ~ '), print_dc_term(D), write(' :='),
    forall(member(G, Guard), ( nl, write('    '), print_literal(G), write(',') )),
    nl, write('    '),
    print_tree(Tree, 4),
    write('.').

%   print_tree(+Tree, +Indent): Tree from the current column (Indent), its
%   other lines indented by Indent.
print_tree(leaf(Comment, Goals), Ind) :-
    (   Comment == "" -> true
    ;   format('% ~w', [Comment]), nl, tab(Ind)
    ),
    (   Goals == [] -> write(true) ; print_goals(Goals, Ind) ).
print_tree(node([Lit-T]), Ind) :- !,
    print_cond(Lit), write(','), nl, tab(Ind),
    print_tree(T, Ind).
print_tree(node([Lit-T|Bs]), Ind) :-
    I4 is Ind+4,
    write('(   '), print_cond(Lit), nl, tab(Ind), write('->  '), print_tree(T, I4),
    forall(member(L-T1, Bs),
           (   L == else
           ->  nl, tab(Ind), write(';   '), print_tree(T1, I4)
           ;   nl, tab(Ind), write(';   '), print_cond(L),
               nl, tab(Ind), write('->  '), print_tree(T1, I4)
           )),
    nl, tab(Ind), write(')').

print_goals([G], _) :- !, print_literal(G).
print_goals([G|Gs], Ind) :- print_literal(G), write(','), nl, tab(Ind), print_goals(Gs, Ind).

print_cond((G -> true)) :- !, print_literal(G).
print_cond((A, B)) :- !, print_conj((A, B)).
print_cond(G) :- print_literal(G).

%   clause_parts(+M, +Node, +Model, +Regs, -Head, -Dist, -Lits, -ScoreGoals-ModelGoals, -Bs):
%   a leaf clause's head, distribution, path literals, the goals of its
%   root model's features and scores (score_goals/9), its model's goals.
clause_parts(M, Node, Model, Regs, Head, Dist, Lits, SGoals-MGoals, Bs) :-
    M:'$ddcl_node'(Node, Info, _),
    node_info_target(Info, target(N, A, Spec)),
    node_info_path(Info, Path),
    tree_head(M, Info, Head, HeadVars, Bs0),
    start_path(HeadVars, Bs0, S0),
    foldl(path_literal(M), Path, S0, S),
    path_state_literals(S, RevLits),
    path_state_names(S, Bs1),
    path_state_regressors(S, Xs0),
    reverse(RevLits, Lits1),
    examples_guard(M, N, A, HeadVars, Lits1, Lits),
    score_goals(M, N, HeadVars, Regs, SGoals, Xs0, Xs1, Bs1, Bs2),
    regressor_vars(Regs, Xs1, Xs),
    (   model_goals(Model, Spec, Xs, Dist, MGoals, Bs2, Bs) -> true
    ;   throw(error(ddc_learn(bad_model(Model, Spec), Node), _))
    ).

%   tree_head(+M, +Info, -Head, -HeadVars, -Names): the DC head of the
%   tree of a node (Info, a node_info record), with a fresh variable for
%   each key argument, named as the node's first variables.
tree_head(M, Info, Head, HeadVars, Bs) :-
    node_info_target(Info, target(N, A, _)),
    node_info_vars(Info, Vars),
    length(HeadInfo, A), append(HeadInfo, _, Vars),
    length(HeadVars, A),
    clause_names(HeadInfo, HeadVars, Bs),
    K =.. [N|HeadVars], dc_term(M, K, Head).

%   examples_guard(+M, +N, +A, +HeadVars, +Lits0, -Lits): a target whose
%   groundings examples/2 declares gets its goal as the first literal of
%   every clause: the head's variables are then bound by the body, as DC's
%   forward reasoning (the particle filter's sweep of h:t+1 clauses) needs,
%   also for a clause whose path tests only negations.
examples_guard(M, N, A, HeadVars, Lits0, Lits) :-
    (   M:'$ddcl_examples'(N/A, H0, G0, _)
    ->  copy_term(H0-G0, H-G),
        H =.. [_|HeadVars],
        renamed_dc(M, G, DG),
        Lits = [DG|Lits0]
    ;   Lits = Lits0
    ).

%   renamed_dc(+M, +Goal, -DC): a goal of the data (time-indexed terms
%   renamed, pair_t1(A, O)) in DC syntax again (pair(A, O):t+1).
renamed_dc(_, V, V) :- var(V), !.
renamed_dc(M, (A, B), (DA, DB)) :- !, renamed_dc(M, A, DA), renamed_dc(M, B, DB).
renamed_dc(M, (A ; B), (DA ; DB)) :- !, renamed_dc(M, A, DA), renamed_dc(M, B, DB).
renamed_dc(M, (A -> B), (DA -> DB)) :- !, renamed_dc(M, A, DA), renamed_dc(M, B, DB).
renamed_dc(M, \+ A, \+ DA) :- !, renamed_dc(M, A, DA).
renamed_dc(M, K ~= V, DK ~= V) :- !, dc_term(M, K, DK).
renamed_dc(M, G, DG) :- callable(G), !, dc_term(M, G, DG).
renamed_dc(_, G, G).

%   start_path(+HeadVars, +Names, -S): the path_state record
%   (ddc_learn_records.pl) at the root: no literal yet, the head's
%   variables, their names.
start_path(HeadVars, Bs, S) :-
    make_path_state([literals([]), values(HeadVars), names(Bs), step(0), regressors([])], S).

%   path_literal(+M, +Step, +S0, -S): S0 and S are path_state records
%   (ddc_learn_records.pl): the step's literal is added to the body, its
%   new variables to the node's.
path_literal(M, step(Id, B), S0, S) :-
    path_state_literals(S0, Lits),
    path_state_values(S0, VT0),
    path_state_names(S0, Bs0),
    path_state_step(S0, K0),
    path_state_regressors(S0, Xs0),
    M:'$ddcl_cand'(Id, _, Spec0),
    node_branch_literal(M, Spec0, VT0, B, Spec, Lit, Bs0, Bs),
    candidate_kind(Spec, Kind),
    candidate_fresh(Spec, Fresh),
    candidate_value(Spec, Val),
    (   B =:= 0, Fresh \== []
    ->  fresh_values(Fresh, FVs), append(VT0, FVs, VT)
    ;   VT = VT0
    ),
    regressor_of(Kind, Lit, Val, X),
    K is K0+1,
    make_path_state([literals([Lit|Lits]), values(VT), names(Bs), step(K),
                     regressors([K0-X|Xs0])], S).

%   regressor_of(+Kind, +Literal, +Val, -X): the variable whose value a
%   step gives the leaf's model (an attribute's value, a count, a mean).
regressor_of(numeric, _, V, V) :- !.
regressor_of(count, (_, length(_, X)), _, X) :- !.
regressor_of(agg_numeric, (_, Call), _, X) :- agg_call(_, _, X, Call), !.   % mean_list(L, X)
regressor_of(_, _, _, none).

%   score_goals(+M, +Target, +HeadVars, +Regs, -Goals, +Xs0, -Xs, +Bs0, -Bs):
%   when Regs has a negative regressor (a score of the root model), Goals
%   compute the root model's features (feature_goals/7) and scores
%   (linear/3), and Xs is Xs0 with the pairs (-1-J)-ScoreJ; else Goals is
%   [] and Xs is Xs0.
score_goals(M, N, HeadVars, Regs, Goals, Xs0, Xs, Bs0, Bs) :-
    (   member(R, Regs), R < 0
    ->  (   M:'$ddcl_root_model'(N, root_model(Fs, Rows)) -> true
        ;   throw(error(ddc_learn(no_root_model(N), N), _))
        ),
        feature_goals(M, Fs, HeadVars, FVs, FGoals, Bs0, Bs1),
        score_vars(Rows, FVs, 1, LGoals, Pairs, Bs1, Bs),
        append(Xs0, Pairs, Xs),
        append(FGoals, LGoals, Goals)
    ;   Goals = [], Xs = Xs0, Bs = Bs0
    ).

%   score_vars(+Rows, +FeatureVars, +J, -Goals, -Pairs, +Bs0, -Bs): one
%   goal linear(FeatureVars, Row, Score) per row, from the J-th score on;
%   Pairs are the regressors (-J)-Score.
score_vars([], _, _, [], [], Bs, Bs).
score_vars([Row|Rows], FVs, J, [linear(FVs, Row, Z)|Gs], [R-Z|Ps], Bs0, Bs) :-
    R is -J,
    new_var('Score', Z, Bs0, Bs1),
    J1 is J+1,
    score_vars(Rows, FVs, J1, Gs, Ps, Bs1, Bs).

%   feature_goals(+M, +Features, +HeadVars, -Vars, -Goals, +Bs0, -Bs): the
%   goals that give each feature of a root model its value, Vars in the
%   order of Features.  A numeric value whose undefined branch is a
%   feature too is read by one goal, (Lit -> U = 0 ; X = Fill, U = 1).
feature_goals(M, Fs, HeadVars, Vs, Goals, Bs0, Bs) :-
    length(Fs, NF), length(Vs, NF),
    pairs_keys_values(FVs, Fs, Vs),
    feature_goals_(FVs, M, HeadVars, FVs, [], Goals, Bs0, Bs).

feature_goals_([], _, _, _, _, [], Bs, Bs).
feature_goals_([F-V|Rest], M, HeadVars, FVs, Done, Goals, Bs0, Bs) :-
    (   memberchk(F, Done)
    ->  Goals = Goals1, Done1 = Done, Bs1 = Bs0
    ;   feature_goal_(M, HeadVars, FVs, F, V, G, Also, Bs0, Bs1),
        Goals = [G|Goals1],
        append([F|Also], Done, Done1)
    ),
    feature_goals_(Rest, M, HeadVars, FVs, Done1, Goals1, Bs1, Bs).

feature_goal_(M, HeadVars, FVs, value(Id, Fill), X, G, Also, Bs0, Bs) :- !,
    M:'$ddcl_cand'(Id, _, Spec),
    node_branch_literal(M, Spec, HeadVars, 0, S1, Lit, Bs0, Bs1),
    candidate_kind(S1, Kind),
    candidate_value(S1, Val),
    regressor_of(Kind, Lit, Val, X0),
    branch_count(Spec, NB), Last is NB-1,
    (   Kind == count
    ->  G = Lit, Also = [], Bs = Bs1
    ;   Last > 0, memberchk(branch(Id, Last)-U, FVs)
    ->  G = (Lit -> U = 0 ; X0 = Fill, U = 1), Also = [branch(Id, Last)],
        new_var('U', U, Bs1, Bs)
    ;   G = (Lit -> true ; X0 = Fill), Also = [], Bs = Bs1
    ),
    X = X0.
feature_goal_(M, HeadVars, _, branch(Id, B), F, (Lit -> F = 1 ; F = 0), [], Bs0, Bs) :- !,
    M:'$ddcl_cand'(Id, _, Spec),
    node_branch_literal(M, Spec, HeadVars, B, _, Lit, Bs0, Bs1),
    new_var('I', F, Bs1, Bs).

regressor_vars([], _, []).
regressor_vars([R|Rs], Xs0, [X|Xs]) :-
    memberchk(R-X, Xs0),
    regressor_vars(Rs, Xs0, Xs).

%   model_goals(+Model, +Spec, +Xs, -Dist, -Goals, +Bs0, -Bs)
model_goals(finite(Ps), discrete(D), _, finite(PVs), [], Bs, Bs) :-
    maplist([P, V, P:V]>>true, Ps, D, PVs).
model_goals(gaussian(Mu, Var), _, _, gaussian(Mu, Var), [], Bs, Bs).
model_goals(poisson(R), _, _, poisson(R), [], Bs, Bs).
model_goals(linear_gaussian(Ws, Var), _, Xs, gaussian(Mean, Var), [linear(Xs, Ws, Mean)], Bs0, Bs) :-
    new_var('Mean', Mean, Bs0, Bs).
model_goals(poisson_log_linear(Ws), _, Xs, poisson(R), [linear(Xs, Ws, Z), R is exp(Z)], Bs0, Bs) :-
    new_var('Z', Z, Bs0, Bs1), new_var('Rate', R, Bs1, Bs).
model_goals(logistic(Ws), discrete([V1, V2]), Xs, finite([P1:V1, P2:V2]),
            [logistic(Xs, Ws, P1), P2 is 1 - P1], Bs0, Bs) :-
    new_var('P1', P1, Bs0, Bs1), new_var('P2', P2, Bs1, Bs).
model_goals(softmax(Rows), discrete(D), Xs, finite(PVs), [softmax(Xs, Rows, Ps)], Bs0, Bs) :-
    length(D, K), length(Ps, K),
    foldl([P, I0-B0, I-B]>>( I is I0+1, atom_concat('P', I, Nm), new_var(Nm, P, B0, B) ),
          Ps, 0-Bs0, _-Bs),
    maplist([P, V, P:V]>>true, Ps, D, PVs).
