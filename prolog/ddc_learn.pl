/*  ddc_learn.pl -- the Prolog side of the DC structure learner: groundings,
    candidate literals, partial possible worlds, learned clauses.

    The search itself (which literal to add, the leaves' statistical
    models, the score) runs in Python (python/ddclearn/); it asks this
    module for the groundings of a target, the literals the declarative
    bias allows at a node of the tree, what each literal says of each
    grounding, and finally for the clauses of the tree in DC syntax.  The
    same predicates can be called by hand from swipl.
*/

:- module(ddc_learn,
          [ learn_load/3,               % +Files, +Options, -Data
            learn_free/1,               % +Data
            learn_targets/2,            % +Data, -Targets
            learn_check/1,              % +Data
            learn_root/4,               % +Data, +Target, +Options, -Root
            learn_candidates/3,         % +Data, +Node, -Candidates
            learn_evaluate/4,           % +Data, +Node, +CandidateIds, -Outcomes
            learn_evaluate_rows/5,      % +Data, +Node, +CandidateId, +Rows, -Outcome
            learn_split/4,              % +Data, +Node, +CandidateId, -Children
            learn_forget/2,             % +Data, +Node
            learn_clause/5,             % +Data, +Node, +Model, +Regressors, -Clause
            learn_clause_text/3,        % +Data, +Clause, -Text
            learn_leaf_text/5,          % +Data, +Node, +ModelText, +Regressors, -Texts
            learn_background_for/3,     % +Data, +Leaves, -Texts
            learn_tree_text/3,          % +Data, +Leaves, -Text
            learn_background/3,         % +Data, +Clauses, -Texts
            learn_groundings/3,         % +Data, +Node, -Groundings
            learn_program_scores/5      % +Data, +ProgramFile, +Targets, +Options, -Scores
          ]).

:- use_module(library(lists)).
:- use_module(library(apply)).
:- use_module(library(assoc)).
:- use_module(library(error)).
:- use_module(library(option)).
:- use_module(library(pairs)).
:- use_module(library(ordsets)).
:- use_module(ddc_dist).
:- use_module(ddc_models).
:- use_module(ddc_learn_data).

:- set_prolog_flag(optimise, true).

/** <module> The DC structure learner's groundings and clauses

A *node* of a tree is a set of groundings of the target's head: rows
r(Bindings, World), Bindings the values of the node's variables (the head's
key arguments, then the variables that relational literals on the path
introduced), World the partial possible world (an assoc Key-Value of the
uncertain facts the proofs on the path have read).  Python keeps each
row's weight and target value; nodes are stored here under an integer id.

A *candidate* is a literal the bias allows at a node, instantiated (which
variables its + arguments take, which constants): one id per distinct
instance, shared by every node it appears at.  Its *outcome* for a row is
a branch index and, for a continuous value, the value (a regressor of
the leaf's model):

    | kind          | branches                                      |
    | discrete      | one per value of the domain, then undefined   |
    | numeric       | defined (value is a regressor), undefined     |
    | threshold     | one per interval, then undefined              |
    | test          | holds, does not hold                          |
    | count         | one (the count is a regressor)                |
    | agg_numeric   | defined (mean/max/min is a regressor), empty  |
    | agg_discrete  | one per value of the mode, then empty         |

A literal with new variables (`-` in a key argument) binds them to its
first solution, so that the clauses of a tree stay mutually exclusive
(DC's requirement): the clause says `(r(X, Y) ~= true -> true)`.

When a proof reads an uncertain fact that the row's world has not
assigned yet, the row is split into one row per value the fact may take
(a discrete distribution exactly, a continuous one by samples), weighted
by their probabilities, and proved again in each: the partial possible
worlds of section 4 of the paper, over which the leaves maximise the
expected log-likelihood.
*/

:- meta_predicate in_world(+, 0).

%!  learn_load(+Files:list, +Options:list, -Data:atom) is det.
%
%   Read data files (learn_data_load/3) and check that the targets can be
%   learned in some order (learn_check/1).  Options: targets(false) for
%   data to score a program on (learn_program_scores/5); seed(S) seeds the
%   samples of continuous uncertain facts; samples(N) (default 20) is how
%   many; max_worlds(K) (default 4096) bounds the partial worlds of one
%   grounding.
learn_load(Files, Options, M) :-
    learn_data_load(Files, Options, M),
    catch(( set_options(M, Options),
            ( option(targets(false), Options) -> true ; learn_check(M) ) ),
          E, ( learn_data_free(M), throw(E) )).

set_options(M, Options) :-
    option(samples(S), Options, 20),
    option(max_worlds(K), Options, 4096),
    must_be(positive_integer, S),
    must_be(positive_integer, K),
    (   option(seed(Seed), Options) -> set_random(seed(Seed)) ; true ),
    dynamic(M:'$ddcl_option'/2),
    retractall(M:'$ddcl_option'(_, _)),
    assertz(M:'$ddcl_option'(samples, S)),
    assertz(M:'$ddcl_option'(max_worlds, K)),
    maplist(declare(M), ['$ddcl_node'/3, '$ddcl_cand'/3, '$ddcl_counter'/2, '$ddcl_consts'/2,
                         '$ddcl_out'/3, '$ddcl_out_done'/1, '$ddcl_node_target'/1]).

declare(M, PI) :- dynamic(M:PI).

%!  learn_free(+Data) is det.
learn_free(M) :- learn_data_free(M).

%!  learn_targets(+Data, -Targets:list(dict)) is det.
%
%   One dict per target: name (the DC head, e.g. "occluded_by(A,O):t+1"),
%   key (Name/KeyArity of the internal predicate), kind (discrete,
%   continuous, count), domain (the values of a discrete target), where
%   (File:Line of its declaration).
learn_targets(M, Targets) :-
    learn_data_targets(M, Ts),
    maplist(target_dict(M), Ts, Targets).

target_dict(M, target(N, A, Spec, Names, File:Line), _{name: Text, predicate: N, arity: A,
                                                        kind: Kind, domain: Dom,
                                                        file: File, line: Line}) :-
    spec_kind(Spec, Kind, Dom),
    head_vars(M, N, A, Names, Vars),
    length(Vs, A), K =.. [N|Vs],
    dc_term(M, K, T),
    clause_names(Vars, Vs, Bs),
    term_text(T, Bs, Text).

spec_kind(discrete(D), discrete, D).
spec_kind(continuous, continuous, []).
spec_kind(count, count, []).

%!  learn_check(+Data) is det.
%
%   The targets read each other only in one direction: no target's modes
%   may reach back to it through other targets (the learned program would
%   be cyclic).
%
%   @error ddc_learn(cyclic_targets(Names), Where)
learn_check(M) :-
    findall(N, M:'$ddcl_target'(N, _, _, _), Ts),
    findall(T-U, ( member(T, Ts), member(U, Ts), U \== T, reads(M, T, U) ), Edges),
    (   member(T0, Ts), reaches(Edges, T0, T0, [T0], Cycle)
    ->  M:'$ddcl_target'(T0, _, _, W),
        throw(error(ddc_learn(cyclic_targets(Cycle), W), _))
    ;   true
    ).

reads(M, T, U) :-
    M:'$ddcl_mode'(_, T/_, _, C, L, _),
    allowed_by_rank(M, T, C, L),
    literal_preds((C, L), Ps), memberchk(U, Ps), !.

reaches(Edges, From, Goal, Seen, [From, To|Path]) :-
    member(From-To, Edges),
    (   To == Goal -> Path = []
    ;   \+ memberchk(To, Seen),
        reaches(Edges, To, Goal, [To|Seen], [To|Path])
    ).

                 /*******************************
                 *             ROOT             *
                 *******************************/

%!  learn_root(+Data, +Target:atom, +Options, -Root:dict) is det.
%
%   The root node of Target (its internal name, e.g. occluded_by_t1):
%   Root = _{node: Id, y: Ys, weight: Ws, example: Es}, one entry per row:
%   the target's value (a discrete one as its index in the domain), the
%   row's weight (1, or the probability of its partial world) and the
%   index of its example (the grounding of the head it comes from).
%
%   @error ddc_learn(target_without_facts(N/A), Where)
learn_root(M, N, _Options, _{node: Id, y: Ys, weight: Ws, example: Es}) :-
    M:'$ddcl_target'(N, A, How, W),
    M:'$ddcl_pred'(N, A, rv(Spec)),
    ( How = own(Names) -> true ; length(Names, A), maplist(=('_'), Names) ),
    head_vars(M, N, A, Names, Vars),
    target_examples(M, N, A, Keys),
    (   Keys == [] -> throw(error(ddc_learn(target_without_facts(N/A), W), _)) ; true ),
    empty_assoc(E0),
    length(Ks, A), append(Ks, [V], As), TG =.. [N|As],
    (   M:'$ddcl_examples'(N/A, _, _, _) -> Missing = false ; Missing = '$none' ),
    Goal = ( once(M:TG) -> Y = V ; Y = Missing ),
    retractall(M:'$ddcl_node_target'(_)), assertz(M:'$ddcl_node_target'(N)),
    foldl(root_rows(M, Spec, Ks, Goal, Y, E0), Keys, 0-Rows-Ys-Ws-Es, _-[]-[]-[]-[]),
    new_node(M, info(target(N, A, Spec), Vars, [], []), Rows, Id).

root_rows(M, Spec, Ks, Goal, Y, E0, Key, I0-Rows0-Ys0-Ws0-Es0, I-Rows-Ys-Ws-Es) :-
    I is I0+1,
    copy_term(Ks-Goal-Y, Key-G-Y1),
    M:'$ddcl_node_target'(N),
    K =.. [N|Key], example_weight(M, K, W),
    alts(M, G, Y1, E0, W, Alts),
    foldl(root_alt(M, Spec, Key, I0), Alts, Rows0-Ys0-Ws0-Es0, Rows-Ys-Ws-Es).

root_alt(M, Spec, Key, I, a(Y, World, F, _), [r(Key, World)|Rows]-[YV|Ys]-[F|Ws]-[I|Es], Rows-Ys-Ws-Es) :-
    (   Y == '$none' -> throw(error(ddc_learn(no_value(Key), M), _)) ; true ),
    target_value(Spec, Y, M, Key, YV).

target_value(discrete(D), Y, M, Key, I) :- !,
    (   nth0(I0, D, Y0), Y0 == Y -> I = I0
    ;   throw(error(ddc_learn(value_not_in_domain(Key, Y, D, unknown), M), _))
    ).
target_value(_, Y, M, Key, Y1) :-
    (   number(Y) -> Y1 = Y
    ;   throw(error(ddc_learn(not_a_number(Key, Y), M), _))
    ).

%   target_examples(+M, +N, +A, -Keys): the groundings of N/A's key: the
%   solutions of examples/2 when declared (a Boolean target given as atoms:
%   an example without a fact is false), else every key with a fact.
target_examples(M, N, A, Keys) :-
    (   M:'$ddcl_examples'(N/A, H0, G0, W)
    ->  internal_key(M, H0-G0, H-G1),
        dc_goal(M, G1, G, W),
        H =.. [_|Ks],
        findall(Ks, M:G, Keys0),
        list_to_set(Keys0, Keys)
    ;   length(Ks, A), append(Ks, [_], As), F =.. [N|As],
        findall(Ks, clause(M:F, true), K1),
        atom_concat('$prob:', N, PN), append(Ks, [_], PAs), PF =.. [PN|PAs],
        (   M:'$ddcl_prob_pred'(N, A) -> findall(Ks, clause(M:PF, true), K2) ; K2 = [] ),
        append(K1, K2, Keys)
    ).

head_vars(M, N, A, Names, Vars) :-
    (   M:'$ddcl_type'(N, A, Types, _, _) -> true
    ;   length(Types, A), maplist(=('_'), Types)
    ),
    foldl(head_var, Names, Types, []-[], Vars-_).

head_var(Name0, Type, Vars0-Used0, Vars-Used) :-
    (   Name0 \== '_' -> Base = Name0 ; type_var_base(Type, Base) ),
    unique_name(Base, Used0, Name),
    append(Vars0, [v(Name, Type)], Vars),
    Used = [Name|Used0].

                 /*******************************
                 *          CANDIDATES          *
                 *******************************/

%!  learn_candidates(+Data, +Node, -Candidates:list(dict)) is det.
%
%   The literals the bias allows at Node: its target's modes whose
%   predicates rank below the target, instantiated in every way the types
%   allow, less the instances already on the path (DreaML uses each mode
%   once per path; here kind(A) and kind(O) of one mode may both be
%   tested).  Each dict: id, mode, kind (see the module
%   header), branches (the number of outcomes), labels (each branch's
%   literal in DC syntax), regressor (per branch: whether it gives a
%   value), root (whether it reads only the head's variables: its outcome
%   per example is the same at every node), fresh (whether it introduces
%   variables).
learn_candidates(M, Node, Cands) :-
    M:'$ddcl_node'(Node, Info, _),
    Info = info(target(TN, TA, _), Vars, Used, _),
    findall(C, node_candidate(M, TN, TA, Vars, Used, C), Cs0),
    list_to_set(Cs0, Cs),
    length(Vars, NV),
    maplist(candidate_dict(M, Vars, NV, TA), Cs, Cands).

node_candidate(M, TN, TA, Vars, Used, Id) :-
    M:'$ddcl_mode'(MId, TN0/TA0, Agg, C, L, W),
    TN0 == TN, ( TA0 == any -> true ; TA0 =:= TA ),
    allowed_by_rank(M, TN, C, L),
    instance(M, Vars, MId, Agg, C, L, W, Spec),
    candidate_id(M, Spec, Id),
    \+ memberchk(Id, Used).                 % a literal at most once on a path

%   allowed_by_rank(+M, +Target, +Cond, +Lit): every predicate the literal
%   reads ranks below the target (unranked predicates rank 0, always
%   allowed), and none is the target itself.
allowed_by_rank(M, T, C, L) :-
    literal_preds((C, L), Ps),
    \+ memberchk(T, Ps),
    ( M:'$ddcl_rank'(T, RT) -> true ; RT = 0 ),
    forall(member(P, Ps), ( M:'$ddcl_rank'(P, RP) -> RP < RT ; true )).

literal_preds(none, []) :- !.
literal_preds((A, B), Ps) :- !,
    literal_preds(A, PA), literal_preds(B, PB), append(PA, PB, Ps).
literal_preds(L, [N]) :- functor(L, N, _).

%   instance(+M, +Vars, +MId, +Agg, +Cond, +Lit, +Where, -Spec) is nondet.
%
%   Spec = cand(MId, Kind, Goal, Ins, Fresh, Val, Dom, Ts, Agg, Lits)
%     Goal   the literal (or Cond-and-literal of an aggregate), internal
%     Ins    [P-V]: template variable V takes node variable P
%     Fresh  [v(Type, V)]: new variables of a relational literal
%     Val    the value variable (an attribute's, an aggregate's result)
%     Lits   lit(Cond, Lit, Locals): an aggregate's condition and literal
%            and their own new variables [v(Type, V)], for the DC text
instance(M, Vars, MId, none, none, L, W, Spec) :- !,
    literal_args(M, L, W, N, KModes, VMode, KTypes, VSpec),
    bind_keys(M, KModes, KTypes, Vars, KArgs, [], Ins0, [], Fresh0),
    (   VSpec == atom
    ->  G =.. [N|KArgs], Kind = test, Val = none, Dom = [], Ts = [], Ins = Ins0
    ;   value_arg(M, VMode, VSpec, Vars, N, KArgs, Ins0, Ins, Val0, Kind, Dom, Ts),
        append(KArgs, [Val0], As), G =.. [N|As],
        ( Kind == test -> Val = none ; Val = Val0 )
    ),
    reverse(Fresh0, Fresh),
    Spec = cand(MId, Kind, G, Ins, Fresh, Val, Dom, Ts, none, lit(true, G, [])).
instance(M, Vars, MId, Agg, Cond, L, W, Spec) :-
    (   Cond == none
    ->  CG = true, CIns = [], CFresh = []
    ;   literal_args(M, Cond, W, CN, CKModes, CVMode, CKTypes, CVSpec),
        bind_keys(M, CKModes, CKTypes, Vars, CKArgs, [], CIns, [], CFresh0),
        reverse(CFresh0, CFresh),
        (   CVSpec == atom -> CG =.. [CN|CKArgs]
        ;   cond_value(CVMode, CV), append(CKArgs, [CV], CAs), CG =.. [CN|CAs]
        )
    ),
    Local = CFresh,
    literal_args(M, L, W, N, KModes, VMode, KTypes, VSpec),
    agg_bind(M, KModes, KTypes, Vars, Local, KArgs, CIns, Ins, UsesLocal),
    (   Local \== [] -> UsesLocal == true ; true ),
    (   Agg == count
    ->  ( VSpec == atom -> LG =.. [N|KArgs] ; cond_value(VMode, LV), append(KArgs, [LV], LAs), LG =.. [N|LAs] ),
        Kind = count, Val = none, Dom = []
    ;   VSpec = rv(Spec0), VMode == (-),
        append(KArgs, [Val], LAs), LG =.. [N|LAs],
        agg_kind(Agg, Spec0, Kind, Dom)
    ),
    conj(CG, LG, G),
    literal_locals(M, LG, KModes, KTypes, KArgs, LLocal),
    append(Local, LLocal, Locals),
    Spec = cand(MId, Kind, G, Ins, [], Val, Dom, [], Agg, lit(CG, LG, Locals)).

%   literal_locals: the aggregated literal's own new variables (- keys).
literal_locals(_, _, Modes, Types, Args, Locals) :-
    findall(v(T, A), ( nth0(I, Modes, Mo), Mo == (-), nth0(I, Types, T), nth0(I, Args, A) ), Locals).

agg_kind(Agg, Spec, agg_numeric, []) :-
    memberchk(Agg, [mean, max, min]), memberchk(Spec, [continuous, count]), !.
agg_kind(Agg, discrete(D), agg_discrete, D) :-
    memberchk(Agg, [mode, antimode]).

cond_value(Mode, V) :- ( Mode == (-) -> true ; Mode == (+) -> true ; V = Mode ).

conj(true, G, G) :- !.
conj(C, G, (C, G)).

%   literal_args(+M, +Lit, +Where, -Name, -KeyModes, -ValueMode, -KeyTypes, -ValueSpec)
literal_args(M, L, W, N, KModes, VMode, KTypes, VSpec) :-
    L =.. [N|Args],
    length(Args, Ar),
    (   Ar > 0, A is Ar-1, learn_data_pred(M, N, A, rv(S))
    ->  append(KModes, [VMode], Args), VSpec = rv(S)
    ;   learn_data_pred(M, N, Ar, atom)
    ->  A = Ar, KModes = Args, VMode = none, VSpec = atom
    ;   throw(error(ddc_learn(unknown_mode_predicate(N/Ar), W), _))
    ),
    (   M:'$ddcl_type'(N, A, KTypes, _, _) -> true
    ;   memberchk(+, KModes) -> throw(error(ddc_learn(no_types(N/A), W), _))
    ;   memberchk(-, KModes) -> throw(error(ddc_learn(no_types(N/A), W), _))
    ;   length(KTypes, A), maplist(=('_'), KTypes)
    ).

%   bind_keys(+M, +Modes, +Types, +Vars, -Args, +Ins0, -Ins, +Fresh0, -Fresh) is nondet.
bind_keys(_, [], [], _, [], Ins, Ins, F, F).
bind_keys(M, [Mo|Ms], [T|Ts], Vars, [A|As], Ins0, Ins, F0, F) :-
    key_arg(M, Mo, T, Vars, A, Ins0, Ins1, F0, F1),
    bind_keys(M, Ms, Ts, Vars, As, Ins1, Ins, F1, F).

key_arg(_, +, T, Vars, V, Ins0, [P-V|Ins0], F, F) :- !,
    nth0(P, Vars, v(_, T0)), T0 == T,
    \+ memberchk(P-_, Ins0).                 % the + arguments of a literal: distinct variables
key_arg(_, -, T, _, V, Ins, Ins, F, [v(T, V)|F]) :- !.
key_arg(M, Mo, T, _, C, Ins, Ins, F, F) :- ( Mo == c ; Mo == '#' ), !,
    type_constants(M, T, Cs), member(C, Cs).
key_arg(_, C, _, _, C, Ins, Ins, F, F) :- atomic(C).

%   agg_bind: + arguments of an aggregated literal take the condition's new
%   variables or the node's; - are local too.
agg_bind(_, [], [], _, _, [], Ins, Ins, _).
agg_bind(M, [Mo|Ms], [T|Ts], Vars, Local, [A|As], Ins0, Ins, Uses) :-
    (   Mo == (+)
    ->  (   member(v(T0, A), Local), T0 == T, Uses = true, Ins1 = Ins0
        ;   nth0(P, Vars, v(_, T0)), T0 == T, Ins1 = [P-A|Ins0]
        )
    ;   key_arg(M, Mo, T, Vars, A, Ins0, Ins1, [], _)
    ),
    agg_bind(M, Ms, Ts, Vars, Local, As, Ins1, Ins, Uses).

%   value_arg(...): the value argument of a random variable's literal.
value_arg(M, VMode, rv(Spec), Vars, N, KArgs, Ins0, Ins, V, Kind, Dom, Ts) :-
    (   VMode == (-)
    ->  Ins = Ins0,
        length(KArgs, A),
        value_kind(M, N/A, Spec, Kind, Dom, Ts)
    ;   VMode == (+)
    ->  M:'$ddcl_type'(N, _, _, VT, _), VT \== none,
        nth0(P, Vars, v(_, T0)), T0 == VT,
        Ins = [P-V|Ins0], Kind = test, Dom = [], Ts = []
    ;   ( VMode == c ; VMode == '#' )
    ->  Spec = discrete(D), member(V, D), Ins = Ins0, Kind = test, Dom = [], Ts = []
    ;   atomic(VMode)
    ->  V = VMode, Ins = Ins0, Kind = test, Dom = [], Ts = []
    ).

value_kind(_, _, discrete(D), discrete, D, []) :- !.
value_kind(M, P, Spec, threshold, [], Ts) :-
    memberchk(Spec, [continuous, count]), M:'$ddcl_thresholds'(P, Ts), !.
value_kind(_, _, Spec, numeric, [], []) :- memberchk(Spec, [continuous, count]), !.
value_kind(_, _, any, test, [], []).

%   type_constants(+M, +Type, -Constants): the constants in argument
%   positions of that type, in the facts.
type_constants(M, T, Cs) :-
    (   M:'$ddcl_consts'(T, Cs) -> true
    ;   findall(C, ( M:'$ddcl_type'(N, A, Ts, _, _), nth1(I, Ts, T0), T0 == T,
                     typed_fact_arg(M, N, A, I, C) ), Cs0),
        sort(Cs0, Cs),
        assertz(M:'$ddcl_consts'(T, Cs))
    ).

typed_fact_arg(M, N, A, I, C) :-
    (   learn_data_pred(M, N, A, rv(_)) -> A1 is A+1 ; A1 = A ),
    functor(F, N, A1),
    clause(M:F, true),
    arg(I, F, C).

%   candidate_id(+M, +Spec, -Id): one id per distinct instance.
candidate_id(M, Spec, Id) :-
    instance_key(Spec, Key),
    (   M:'$ddcl_cand'(Id0, Key, _) -> Id = Id0
    ;   next_id(M, cand, Id),
        assertz(M:'$ddcl_cand'(Id, Key, Spec))
    ).

instance_key(Spec, k(MId, G1)) :-
    Spec = cand(MId, _, G, Ins, _, _, _, _, _, _),
    copy_term(G-Ins, G1-Ins1),
    maplist([P-'$in'(P)]>>true, Ins1),
    numbervars(G1, 0, _).

next_id(M, Kind, Id) :-
    (   retract(M:'$ddcl_counter'(Kind, Id0)) -> Id is Id0+1 ; Id = 1 ),
    assertz(M:'$ddcl_counter'(Kind, Id)).

candidate_dict(M, Vars, NV, TA, Id, _{id: Id, mode: MId, kind: Kind, branches: NB, labels: Labels,
                                      regressor: Regs, root: Root, fresh: Fresh, where: Where}) :-
    M:'$ddcl_cand'(Id, _, Spec),
    Spec = cand(MId, Kind, _, Ins, F, _, _, _, _, _),
    M:'$ddcl_mode'(MId, _, _, _, _, File:Line),
    format(atom(Where), '~w:~w', [File, Line]),
    branch_count(Spec, NB),
    length(VarTerms, NV),
    clause_names(Vars, VarTerms, Bs0),
    NB1 is NB-1, numlist(0, NB1, BIs),
    maplist(branch_label(M, Spec, VarTerms, Bs0), BIs, Labels),
    maplist(branch_regressor(Kind), BIs, Regs),
    (   forall(member(P-_, Ins), P < TA) -> Root = true ; Root = false ),
    ( F == [] -> Fresh = false ; Fresh = true ).

branch_count(cand(_, discrete, _, _, _, _, D, _, _, _), N) :- !, length(D, K), N is K+1.
branch_count(cand(_, agg_discrete, _, _, _, _, D, _, _, _), N) :- !, length(D, K), N is K+1.
branch_count(cand(_, threshold, _, _, _, _, _, Ts, _, _), N) :- !, length(Ts, K), N is K+2.
branch_count(cand(_, count, _, _, _, _, _, _, _, _), 1) :- !.
branch_count(_, 2).

branch_regressor(numeric, 0, true) :- !.
branch_regressor(count, 0, true) :- !.
branch_regressor(agg_numeric, 0, true) :- !.
branch_regressor(_, _, false).

branch_label(M, Spec, VarTerms, Bs0, B, Text) :-
    copy_term(Spec, S1),
    S1 = cand(_, _, _, Ins, Fresh, _, _, _, _, _),
    maplist(bind_in(VarTerms), Ins),
    fresh_names(Fresh, Bs0, Bs1),
    branch_literal(M, S1, B, Lit, Bs1, Bs),
    term_text(Lit, Bs, Text).

bind_in(VarTerms, P-V) :- nth0(P, VarTerms, V).

                 /*******************************
                 *   OUTCOMES IN PARTIAL WORLDS *
                 *******************************/

%!  learn_evaluate(+Data, +Node, +CandidateIds:list, -Outcomes:list(dict)) is det.
%
%   For each candidate, its outcome in each row of Node: a dict of lists
%   row (the node's row index, from 0), branch, factor (the probability of
%   the partial world in which the outcome holds, relative to the row's),
%   x (the value, NaN where none), pure (false where the proof read an
%   uncertain fact: the outcome may differ in another world).  A row
%   appears once per partial world it splits into.
learn_evaluate(M, Node, Ids, Outs) :-
    M:'$ddcl_node'(Node, _, Rows),
    maplist(evaluate_rows(M, Rows), Ids, Outs).

%!  learn_evaluate_rows(+Data, +Node, +CandidateId, +RowIndices, -Outcome:dict) is det.
%
%   learn_evaluate/4 for some rows of Node only (those whose outcome at the
%   root was not pure).
learn_evaluate_rows(M, Node, Id, Is, Out) :-
    M:'$ddcl_node'(Node, _, Rows),
    findall(I-R, ( member(I, Is), nth0(I, Rows, R) ), IRs),
    evaluate_indexed(M, IRs, Id, Out).

evaluate_rows(M, Rows, Id, Out) :-
    length(Rows, N), N1 is N-1,
    ( N1 >= 0 -> numlist(0, N1, Is) ; Is = [] ),
    pairs_keys_values(IRs, Is, Rows),
    evaluate_indexed(M, IRs, Id, Out).

evaluate_indexed(M, IRs, Id, _{row: Rs, branch: Bs, factor: Fs, x: Xs, pure: Ps}) :-
    M:'$ddcl_cand'(Id, _, Spec),
    outcome_goal(M, Spec, Bind, Goal, Out),
    node_outcomes(M, IRs, Bind, Goal, Out, Results),
    outcome_lists(Results, Rs, Bs, Fs, Xs, Ps).

outcome_lists([], [], [], [], [], []).
outcome_lists([res(I, _, _, F, P, o(B, X, _))|T], [I|Is], [B|Bs], [F|Fs], [X|Xs], [P|Ps]) :-
    outcome_lists(T, Is, Bs, Fs, Xs, Ps).

%   node_outcomes(+M, +IndexedRows, ?Bind, +Goal, ?Out, -Results): the
%   outcome of Goal in each row and partial world, res(I, Bindings, World,
%   Factor, Pure, Out) in row order.  A row whose proof reads no uncertain
%   fact the row's world has not assigned is proved once, in a failure-
%   driven loop (no copy of the goal); only the others split their worlds
%   (alts/6).
node_outcomes(M, IRs, Bind, Goal, Out, Results) :-
    findall(R, ( member(I-r(Bs, W), IRs), row_outcome(Bind, Goal, Out, I, Bs, W, R) ), Rs),
    foldl(world_outcomes(M, Bind, Goal, Out), Rs, Results, []).

row_outcome(Bind, Goal, Out, I, Bs, W, R) :-
    nb_setval(ddcl_touched, false),
    Bind = Bs,
    catch(( in_world(W, Goal) -> R0 = ok ; R0 = failed ), ddcl_need(_, _), R0 = need),
    (   R0 == ok
    ->  nb_getval(ddcl_touched, T),
        ( T == true -> P = false ; P = true ),
        R = res(I, Bs, W, 1.0, P, Out)
    ;   R0 == need
    ->  R = slow(I, Bs, W)
    ;   throw(error(ddc_learn(goal_failed(Goal), data), _))
    ).

world_outcomes(_, _, _, _, R, [R|T], T) :- R = res(_, _, _, _, _, _), !.
world_outcomes(M, Bind, Goal, Out, slow(I, Bs, W), L, T) :-
    copy_term(Bind-Goal-Out, Bs-G-O),
    alts(M, G, O, W, 1.0, Alts),
    foldl(alt_result(I, Bs), Alts, L, T).

alt_result(I, Bs, a(O, W, F, P), [res(I, Bs, W, F, P, O)|T], T).

%   outcome_goal(+M, +Spec, -Bind, -Goal, -Out): Goal, once Bind (the node
%   variables' values) is bound, always succeeds with Out = o(Branch, X,
%   FreshValues).
%   The goal is compiled once per candidate, as the clause
%   '$ddcl_out'(Id, Bind, Out) :- Goal of the data module, so that each row
%   runs compiled code instead of a meta-call of the whole conjunction.
outcome_goal(M, Spec, Bind, M:'$ddcl_out'(Id, Bind, Out), Out) :-
    candidate_id(M, Spec, Id),
    (   M:'$ddcl_out_done'(Id) -> true
    ;   copy_term(Spec, cand(_, Kind, G, Ins, Fresh, Val, Dom, Ts, Agg, _)),
        bind_goal(Ins, BindList, BG),
        fresh_values(Fresh, FVs),
        kind_goal(Kind, Agg, M:G, Val, Dom, Ts, B, X, KG),
        optimised_assert(M, ('$ddcl_out'(Id, BindList, o(B, X, FVs)) :- BG, KG)),
        assertz(M:'$ddcl_out_done'(Id))
    ).

%   fresh_values(+Fresh, -Vars): the variables of [v(Type, Var)], shared
%   (findall/3 would copy them).
fresh_values([], []).
fresh_values([v(_, V)|Fs], [V|Vs]) :- fresh_values(Fs, Vs).

optimised_assert(M, Clause) :-
    current_prolog_flag(optimise, Old),
    setup_call_cleanup(set_prolog_flag(optimise, true), assertz(M:Clause),
                       set_prolog_flag(optimise, Old)).

%   bind_goal(+Ins, ?Bindings, -Goal): unify each template variable with
%   its node variable's value in the row.
bind_goal([], _, true).
bind_goal([P-V|Ins], Bs, ( nth0(P, Bs, V), G )) :- bind_goal(Ins, Bs, G).

kind_goal(discrete, _, G, V, Dom, _, B, X, Goal) :-
    length(Dom, K),
    Goal = ( once(G) -> ddc_learn:domain_index(V, Dom, B), X = nan ; B = K, X = nan ).
kind_goal(numeric, _, G, V, _, _, B, X, Goal) :-
    Goal = ( once(G) -> ddc_learn:numeric_value(V, X), B = 0 ; B = 1, X = nan ).
kind_goal(threshold, _, G, V, _, Ts, B, X, Goal) :-
    length(Ts, K), K1 is K+1,
    Goal = ( once(G) -> ddc_learn:numeric_value(V, X0), ddc_learn:bin(X0, Ts, 0, B), X = nan
           ; B = K1, X = nan ).
kind_goal(test, _, G, _, _, _, B, X, Goal) :-
    Goal = ( once(G) -> B = 0, X = nan ; B = 1, X = nan ).
kind_goal(count, _, G, _, _, _, B, X, Goal) :-
    Goal = ( findall(x, G, L), length(L, X), B = 0 ).
kind_goal(agg_numeric, Agg, G, V, _, _, B, X, Goal) :-
    Goal = ( findall(V, G, L),
             (   L == [] -> B = 1, X = nan
             ;   ddc_learn:numeric_list(L), ddc_learn:aggregate(Agg, L, X), B = 0
             ) ).
kind_goal(agg_discrete, Agg, G, V, Dom, _, B, X, Goal) :-
    length(Dom, K),
    Goal = ( findall(V, G, L),
             (   L == [] -> B = K, X = nan
             ;   ddc_learn:aggregate(Agg, L, Mo), ddc_learn:domain_index(Mo, Dom, B), X = nan
             ) ).

domain_index(V, Dom, B) :-
    (   nth0(B0, Dom, V0), V0 == V -> B = B0
    ;   throw(error(ddc_learn(value_not_in_domain(value, V, Dom, unknown), data), _))
    ).

numeric_value(V, X) :-
    (   number(V) -> X = V
    ;   throw(error(ddc_learn(not_a_number(value, V), data), _))
    ).

numeric_list(L) :-
    (   maplist(number, L) -> true
    ;   member(V, L), \+ number(V) -> throw(error(ddc_learn(not_a_number(value, V), data), _))
    ).

bin(X, [], B, B) :- !, number(X).
bin(X, [T|Ts], B0, B) :- ( X < T -> B = B0 ; B1 is B0+1, bin(X, Ts, B1, B) ).

aggregate(mean, L, X) :- mean_list(L, X).
aggregate(max, L, X) :- max_list(L, X).
aggregate(min, L, X) :- min_list(L, X).
aggregate(mode, L, X) :- mode_list(L, X).
aggregate(antimode, L, X) :- antimode_list(L, X).

%   alts(+M, +Goal, +Out, +World, +F, -Alts): the outcomes of Goal in the
%   partial worlds that extend World, a(Out, World1, F1, Pure) each; F1 is
%   F times the probability of what World1 adds.  Goal is proved with
%   World as the assignment pick/3 reads; a pick of an unassigned key
%   splits the world on that key's values and proves again in each.
alts(M, Goal, Out, World, F, Alts) :-
    M:'$ddcl_option'(max_worlds, Max),
    M:'$ddcl_option'(samples, S),
    alts_(Goal, Out, World, F, S, Max, 0, _, Alts, []).

alts_(Goal, Out, World, F, S, Max, N0, N, Alts, Tail) :-
    nb_setval(ddcl_touched, false),
    copy_term(Goal-Out, G-O),
    catch(( in_world(World, G) -> R = ok(O) ; R = failed ),
          ddcl_need(K, D), R = need(K, D)),
    nb_getval(ddcl_touched, T),
    (   R = ok(O1)
    ->  ( T == true -> Pure = false ; Pure = true ),
        N is N0+1,
        (   N > Max -> throw(error(ddc_learn(too_many_worlds(Max), data), _)) ; true ),
        Alts = [a(O1, World, F, Pure)|Tail]
    ;   R = need(K1, D1)
    ->  dist_points(D1, S, Points),
        foldl(split_world(Goal, Out, World, F, S, Max, K1), Points, N0-Alts, N-Tail0),
        Tail0 = Tail
    ;   throw(error(ddc_learn(goal_failed(Goal), data), _))
    ).

split_world(Goal, Out, World, F, S, Max, K, P-V, N0-Alts, N-Tail) :-
    put_assoc(K, World, V, W1),
    F1 is F*P,
    alts_(Goal, Out, W1, F1, S, Max, N0, N1, Alts0, Tail),
    mark_impure(Alts0, Tail, Alts),
    N = N1.

mark_impure(L, Tail, L) :- L == Tail, !.
mark_impure([a(O, W, F, _)|T0], Tail, [a(O, W, F, false)|T]) :- mark_impure(T0, Tail, T).

in_world(World, G) :-
    b_setval(ddcl_assign, World),
    call(G).

                 /*******************************
                 *            SPLITS            *
                 *******************************/

%!  learn_split(+Data, +Node, +CandidateId, -Children:list(dict)) is det.
%
%   Split Node by a candidate: one child node per branch, each dict node
%   (its id), row (the parent rows its rows come from, in order), factor,
%   x.  A branch that binds new variables gives its child those variables.
learn_split(M, Node, Id, Children) :-
    M:'$ddcl_node'(Node, Info, Rows),
    M:'$ddcl_cand'(Id, _, Spec),
    branch_count(Spec, NB),
    outcome_goal(M, Spec, Bind, Goal, Out),
    length(Rows, NR), NR1 is NR-1,
    ( NR1 >= 0 -> numlist(0, NR1, Is) ; Is = [] ),
    pairs_keys_values(IRs, Is, Rows),
    node_outcomes(M, IRs, Bind, Goal, Out, Results),
    findall(B-(I-r(Bs1, W1)-F-X),
            ( member(res(I, Bs, W1, F, _, o(B, X, FVs)), Results),
              ( B =:= 0, FVs \== [] -> append(Bs, FVs, Bs1) ; Bs1 = Bs ) ),
            Pairs),
    NB1 is NB-1, numlist(0, NB1, BIs),
    Info = info(T, Vars, Used, Path),
    Spec = cand(_, _, _, _, Fresh, _, _, _, _, _),
    maplist(child(M, T, Vars, Used, Path, Id, Fresh, Pairs), BIs, Children).

child(M, T, Vars, Used, Path, Id, Fresh, Pairs, B,
      _{node: C, branch: B, row: Rs, factor: Fs, x: Xs}) :-
    findall(R-I-F-X, member(B-(I-R-F-X), Pairs), Ls),
    findall(R, member(R-_-_-_, Ls), Rows),
    findall(I, member(_-I-_-_, Ls), Rs),
    findall(F, member(_-_-F-_, Ls), Fs),
    findall(X, member(_-_-_-X, Ls), Xs),
    (   B =:= 0, Fresh \== []
    ->  findall(Name, member(v(Name, _), Vars), Used0),
        foldl(fresh_var, Fresh, Vars-Used0, Vars1-_)
    ;   Vars1 = Vars
    ),
    append(Path, [step(Id, B)], Path1),
    new_node(M, info(T, Vars1, [Id|Used], Path1), Rows, C).

fresh_var(v(Type, _), Vars0-Used0, Vars-[Name|Used0]) :-
    type_var_base(Type, Base),
    unique_name(Base, Used0, Name),
    append(Vars0, [v(Name, Type)], Vars).

new_node(M, Info, Rows, Id) :-
    next_id(M, node, Id),
    assertz(M:'$ddcl_node'(Id, Info, Rows)).

%!  learn_forget(+Data, +Node) is det.
%
%   Drop a node's rows (a branch the search did not keep, a lookahead).
learn_forget(M, Node) :-
    retractall(M:'$ddcl_node'(Node, _, _)).

%!  learn_groundings(+Data, +Node, -Groundings:list) is det.
%
%   The node's rows as terms Head-World: the target's head with the row's
%   bindings and the partial world's assignment as Key=Value pairs (for
%   inspection from swipl).
learn_groundings(M, Node, Gs) :-
    M:'$ddcl_node'(Node, info(target(N, A, _), _, _, _), Rows),
    findall(H-Ps, ( member(r(Bs, W), Rows), length(Ks, A), append(Ks, _, Bs),
                    K =.. [N|Ks], dc_term(M, K, H),
                    assoc_to_list(W, Ps0), maplist(world_pair(M), Ps0, Ps) ),
            Gs).

world_pair(M, Key-V, DK=V) :- dc_term(M, Key, DK).

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
learn_clause(M, Node, Model, Regs, clause((Head ~ Dist := Body), Bs)) :-
    clause_parts(M, Node, Model, Regs, Head, Dist, Lits, Goals, Bs),
    append(Lits, Goals, Ls),
    ( Ls == [] -> Body = true ; conj_list(Ls, Body) ).

%!  learn_leaf_text(+Data, +Node, +ModelText, +Regressors, -Texts:dict) is det.
%
%   learn_clause/5 for Python: the model as Prolog text; Texts has clause
%   (the clause in DC syntax), distribution (its head's) and model (the
%   statistical model's goals, "" without regressors).
learn_leaf_text(M, Node, ModelText, Regs, _{clause: CT, distribution: DT, model: MT}) :-
    term_string(Model, ModelText),
    clause_parts(M, Node, Model, Regs, Head, Dist, Lits, Goals, Bs),
    append(Lits, Goals, Ls),
    ( Ls == [] -> Body = true ; conj_list(Ls, Body) ),
    learn_clause_text(M, clause((Head ~ Dist := Body), Bs), CT),
    term_text(Dist, Bs, DT),
    (   Goals == [] -> MT = ""
    ;   conj_list(Goals, GC), term_text(GC, Bs, MT0), strip_parens(MT0, MT)
    ).

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
    M:'$ddcl_node'(N0, info(target(N, A, Spec), Vars, _, _), _),
    length(HeadInfo, A), append(HeadInfo, _, Vars),
    length(HeadVars, A),
    clause_names(HeadInfo, HeadVars, Bs0),
    K =.. [N|HeadVars], dc_term(M, K, Head),
    examples_guard(M, N, A, HeadVars, [], Guard),
    term_string(Model0, MT0),
    once(model_goals(Model0, Spec, _, Dist0, _, [], _)),
    dist_template(Dist0, Dist, Bs0, Bs1),
    maplist(leaf_item(M), Leaves, Items),
    tree_node(Items, t(M, Spec, Dist), s([], HeadVars, Bs1, 0, []), Bs, Tree),
    dedupe_names(Bs, Bs2),
    copy_term(t(Head, Dist, Guard, Tree)-Bs2, t(H1, D1, G1, T1)-Bs3),
    maplist([Name=V]>>( var(V) -> V = '$VAR'(Name) ; true ), Bs3),
    term_variables(t(H1, D1, G1, T1), Rest),
    maplist(=('$VAR'('_')), Rest),
    with_output_to(string(Text), print_tree_clause(H1, D1, G1, T1)).

leaf_item(M, [Node, MT, Regs, Comment], Path-leaf(Model, Regs, Comment)) :-
    M:'$ddcl_node'(Node, info(_, _, _, Path), _),
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
%   RemainingPath-leaf(Model, Regressors, Comment)) from path state S (see
%   path_literal/4); Tree is leaf(Comment, Goals) or node([Lit-Tree, ...]).
tree_node([[]-leaf(Model, Regs, Comment)], t(_, Spec, Dist), s(_, _, Bs0, _, Xs0), Bs,
          leaf(Comment, Goals)) :- !,
    regressor_vars(Regs, Xs0, Xs),
    once(model_goals(Model, Spec, Xs, D, Goals0, Bs0, Bs)),
    leaf_params(D, Dist, Eqs),
    append(Goals0, Eqs, Goals).
tree_node(Items, Ctx, S0, Bs, node(Branches)) :-
    Items = [[step(Id, _)|_]-_|_],
    forall(member(P-_, Items), P = [step(Id, _)|_]),
    group_branches(Items, Groups),
    tree_branches(Groups, Id, Ctx, S0, Bs, Branches0),
    Ctx = t(M, _, _),
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
    M:'$ddcl_cand'(Id, _, cand(_, Kind, _, _, _, _, _, Ts, _, _)),
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

tree_branches([], _, _, s(_, _, Bs, _, _), Bs, []).
tree_branches([B-Sub|Gs], Id, Ctx, S0, Bs, [Lit-T|Ts]) :-
    Ctx = t(M, _, _),
    path_literal(M, step(Id, B), S0, S1),
    S1 = s([Lit|_], _, _, _, _),
    tree_node(Sub, Ctx, S1, Bs1, T),
    S0 = s(Ls, VT, _, K, Xs),
    tree_branches(Gs, Id, Ctx, s(Ls, VT, Bs1, K, Xs), Bs, Ts).

%   dedupe_names(+Bs0, -Bs): the first name of each variable (a leaf's
%   model variable bound to the head's parameter keeps the head's name).
dedupe_names(Bs0, Bs) :-
    foldl([N=V, A0, A]>>( member(_=W, A0), W == V -> A = A0 ; append(A0, [N=V], A) ),
          Bs0, [], Bs).

print_tree_clause(H, D, Guard, Tree) :-
    print_literal(H), write(' ~ '), print_term_(D), write(' :='),
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

clause_parts(M, Node, Model, Regs, Head, Dist, Lits, Goals, Bs) :-
    M:'$ddcl_node'(Node, info(target(N, A, Spec), Vars, _, Path), _),
    length(HeadInfo, A), append(HeadInfo, _, Vars),
    length(HeadVars, A),
    clause_names(HeadInfo, HeadVars, Bs0),
    K =.. [N|HeadVars], dc_term(M, K, Head),
    foldl(path_literal(M), Path, s([], HeadVars, Bs0, 0, []), s(RevLits, _, Bs1, _, Xs0)),
    reverse(RevLits, Lits1),
    examples_guard(M, N, A, HeadVars, Lits1, Lits),
    regressor_vars(Regs, Xs0, Xs),
    (   model_goals(Model, Spec, Xs, Dist, Goals, Bs1, Bs) -> true
    ;   throw(error(ddc_learn(bad_model(Model, Spec), Node), _))
    ).

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

%   path_literal(+M, +Step, +S0, -S): S = s(LiteralsReversed, VarTerms,
%   Bindings, StepIndex, StepIndex-ValueVariable pairs).
path_literal(M, step(Id, B), s(Lits, VT0, Bs0, K0, Xs0), s([Lit|Lits], VT, Bs, K, [K0-X|Xs0])) :-
    M:'$ddcl_cand'(Id, _, Spec0),
    copy_term(Spec0, Spec),
    Spec = cand(_, Kind, _, Ins, Fresh, Val, _, _, _, _),
    maplist(bind_in(VT0), Ins),
    fresh_names(Fresh, Bs0, Bs1),
    branch_literal(M, Spec, B, Lit, Bs1, Bs),
    (   B =:= 0, Fresh \== []
    ->  fresh_values(Fresh, FVs), append(VT0, FVs, VT)
    ;   VT = VT0
    ),
    regressor_of(Kind, Lit, Val, X),
    K is K0+1.

%   regressor_of(+Kind, +Literal, +Val, -X): the variable whose value a
%   step gives the leaf's model (an attribute's value, a count, a mean).
regressor_of(numeric, _, V, V) :- !.
regressor_of(count, (_, length(_, X)), _, X) :- !.
regressor_of(agg_numeric, (_, Call), _, X) :- compound(Call), Call \= (_ == _), !, arg(2, Call, X).
regressor_of(_, _, _, none).

regressor_vars([], _, []).
regressor_vars([R|Rs], Xs0, [X|Xs]) :-
    memberchk(R-X, Xs0),
    regressor_vars(Rs, Xs0, Xs).

fresh_names(Fresh, Bs0, Bs) :-
    foldl(fresh_name, Fresh, Bs0, Bs).

fresh_name(v(Type, V), Bs0, Bs) :-
    (   var(V)
    ->  type_var_base(Type, Base),
        findall(N, member(N=_, Bs0), Used),
        unique_name(Base, Used, Name),
        append(Bs0, [Name=V], Bs)
    ;   Bs = Bs0
    ).

%   branch_literal(+M, +Spec, +Branch, -Literal, +Bs0, -Bs): the branch's
%   body literal in DC syntax; names for its new variables added to Bs.
branch_literal(M, cand(_, Kind, G, _, Fresh, Val, Dom, Ts, Agg, lit(CG, LG, Locals)), B, Lit,
               Bs0, Bs) :-
    fresh_names(Locals, Bs0, Bs00),
    value_name(M, Kind, Agg, LG, Val, Bs00, Bs1),
    dc_literal(M, G, DG),
    branch_literal_(Kind, B, DG, Fresh, Val, Dom, Ts, Agg, CG, LG, M, Lit, Bs1, Bs).

branch_literal_(discrete, B, K ~= V, _, V, Dom, _, _, _, _, _, Lit, Bs, Bs) :-
    (   nth0(B, Dom, C) -> V = C, Lit = (K ~= V) ; Lit = (\+ K ~= _) ).
branch_literal_(numeric, B, K ~= V, _, V, _, _, _, _, _, _, Lit, Bs, Bs) :-
    (   B =:= 0 -> Lit = (K ~= V) ; Lit = (\+ K ~= _) ).
branch_literal_(threshold, B, K ~= V, _, V, _, Ts, _, _, _, _, Lit, Bs, Bs) :-
    length(Ts, NT),
    (   B =:= 0 -> Ts = [T|_], Lit = (K ~= V, V < T)
    ;   B =:= NT -> last(Ts, T), Lit = (K ~= V, V >= T)
    ;   B < NT -> B0 is B-1, nth0(B0, Ts, T0), nth0(B, Ts, T1), Lit = (K ~= V, V >= T0, V < T1)
    ;   Lit = (\+ K ~= _)
    ).
branch_literal_(test, B, DG, Fresh, _, _, _, _, _, _, _, Lit, Bs, Bs) :-
    (   B =:= 0 -> ( Fresh == [] -> Lit = DG ; Lit = (DG -> true) )
    ;   Lit = (\+ DG)
    ).
branch_literal_(count, _, _, _, _, _, _, _, CG, LG, M, Lit, Bs0, Bs) :-
    agg_goal(M, CG, LG, DG),
    list_var(Bs0, Bs1, L),
    count_var(M, LG, Bs1, Bs, X),
    Lit = (findall_forward(x, DG, L), length(L, X)).
branch_literal_(agg_numeric, B, _, _, V, _, _, Agg, CG, LG, M, Lit, Bs0, Bs) :-
    agg_goal(M, CG, LG, DG),
    list_var(Bs0, Bs1, L),
    (   B =:= 0
    ->  agg_call(Agg, L, X, Call), agg_result_var(M, Agg, LG, Bs1, Bs, X),
        Lit = (findall_forward(V, DG, L), Call)
    ;   Bs = Bs1, Lit = (findall_forward(V, DG, L), L == [])
    ).
branch_literal_(agg_discrete, B, _, _, V, Dom, _, Agg, CG, LG, M, Lit, Bs0, Bs) :-
    agg_goal(M, CG, LG, DG),
    list_var(Bs0, Bs, L),
    (   nth0(B, Dom, C)
    ->  agg_call(Agg, L, C, Call), Lit = (findall_forward(V, DG, L), Call)
    ;   Lit = (findall_forward(V, DG, L), L == [])
    ).

agg_goal(M, CG, LG, DG) :-
    (   CG == true -> dc_literal(M, LG, DG)
    ;   dc_literal(M, CG, DC), dc_literal(M, LG, DL), DG = (DC, DL)
    ).

agg_call(mean, L, X, mean_list(L, X)).
agg_call(max, L, X, max_list(L, X)).
agg_call(min, L, X, min_list(L, X)).
agg_call(mode, L, X, mode_list(L, X)).
agg_call(antimode, L, X, antimode_list(L, X)).

list_var(Bs0, Bs, L) :-
    findall(N, member(N=_, Bs0), Used),
    unique_name('L', Used, Name),
    append(Bs0, [Name=L], Bs).

%   value_name: a name for the value variable of an attribute (Distance
%   for distance_t(A, O, Distance)), of an aggregate's elements.
value_name(M, Kind, _, LG, V, Bs0, Bs) :-
    (   var(V), \+ ( member(_=V0, Bs0), V0 == V ), Kind \== count
    ->  functor(LG, N, _), base_name(M, N, B0), capitalise(B0, Base),
        findall(Nm, member(Nm=_, Bs0), Used),
        unique_name(Base, Used, Name),
        append(Bs0, [Name=V], Bs)
    ;   Bs = Bs0
    ).

count_var(M, LG, Bs0, Bs, X) :-
    functor(LG, N, _), base_name(M, N, B0), capitalise(B0, C),
    atom_concat('N', C, Base),
    findall(Nm, member(Nm=_, Bs0), Used),
    unique_name(Base, Used, Name),
    append(Bs0, [Name=X], Bs).

agg_result_var(M, Agg, LG, Bs0, Bs, X) :-
    functor(LG, N, _), base_name(M, N, B0), capitalise(B0, C),
    capitalise(Agg, A), atom_concat(A, C, Base),
    findall(Nm, member(Nm=_, Bs0), Used),
    unique_name(Base, Used, Name),
    append(Bs0, [Name=X], Bs).

base_name(M, N, B) :- ( M:'$ddcl_timed'(N, B0, _) -> B = B0 ; B = N ).

%   dc_literal(+M, +Internal, -DC): an internal literal in DC syntax.
dc_literal(M, (A, B), (DA, DB)) :- !, dc_literal(M, A, DA), dc_literal(M, B, DB).
dc_literal(M, G, DG) :-
    G =.. [N|As],
    length(As, Ar),
    (   Ar > 0, A is Ar-1, learn_data_pred(M, N, A, rv(_))
    ->  append(Ks, [V], As), K =.. [N|Ks], dc_term(M, K, DK), DG = (DK ~= V)
    ;   dc_term(M, G, DG)
    ).

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

new_var(Base, V, Bs0, Bs) :-
    findall(N, member(N=_, Bs0), Used),
    unique_name(Base, Used, Name),
    append(Bs0, [Name=V], Bs).

conj_list([G], G) :- !.
conj_list([G|Gs], (G, C)) :- conj_list(Gs, C).

%!  learn_background(+Data, +Clauses:list, -Texts:list(string)) is det.
%
%   The background knowledge the clauses need (the data's DC clauses and
%   derived predicates their bodies call, transitively), each in DC
%   syntax as a string: DreaML's Prolog rules over random variables become
%   derived DC clauses (`districtClientAccount(D, C, A) :=
%   clientDistrict(C, D) ~= true, hasAccount(C, A) ~= true.`).
learn_background(M, Clauses, Texts) :-
    findall(P, ( member(clause(C, _), Clauses), clause_calls(C, P) ), Ps0),
    sort(Ps0, Ps),
    background_closure(M, Ps, [], Needed),
    findall(W-T, ( member(N/A, Needed), functor(H, N, A),
                   M:'$ddcl_background'(H0, C, W), \+ H0 \= H,
                   background_text(M, C, W, T) ), WTs),
    sort(WTs, Sorted),
    pairs_values(Sorted, Texts).

clause_calls((_ ~ _ := B), P) :- body_pred(B, P).

body_pred(V, _) :- var(V), !, fail.
body_pred((A, B), P) :- !, ( body_pred(A, P) ; body_pred(B, P) ).
body_pred((A ; B), P) :- !, ( body_pred(A, P) ; body_pred(B, P) ).
body_pred((A -> B), P) :- !, ( body_pred(A, P) ; body_pred(B, P) ).
body_pred(\+ A, P) :- !, body_pred(A, P).
body_pred(findall_forward(_, G, _), P) :- !, body_pred(G, P).
body_pred(findall(_, G, _), P) :- !, body_pred(G, P).
body_pred(K ~= _, P) :- !, internal_name(K, P).
body_pred(G, P) :- callable(G), internal_name(G, P).

internal_name(X:TE, N/A) :- nonvar(TE), TE = T+1, T == t, !, functor(X, N0, A),
    atom_concat(N0, '_t1', N).
internal_name((X:T)+1, N/A) :- T == t, !, functor(X, N0, A), atom_concat(N0, '_t1', N).
internal_name(X:T, N/A) :- T == t, !, functor(X, N0, A), atom_concat(N0, '_t', N).
internal_name(G, N/A) :- functor(G, N, A).

background_closure(_, [], Acc, Acc).
background_closure(M, [P|Ps], Acc, Needed) :-
    (   memberchk(P, Acc)
    ->  background_closure(M, Ps, Acc, Needed)
    ;   P = N/A, functor(H, N, A),
        findall(Q, ( M:'$ddcl_background'(H0, C, _), \+ H0 \= H, background_calls(C, Q) ), Qs),
        (   M:'$ddcl_background'(H1, _, _), \+ H1 \= H -> Acc1 = [P|Acc] ; Acc1 = Acc ),
        append(Qs, Ps, Ps1),
        background_closure(M, Ps1, Acc1, Needed)
    ).

background_calls((_ ~ _ := B), Q) :- !, body_pred(B, Q).
background_calls((_ := B), Q) :- !, body_pred(B, Q).
background_calls((_ :- B), Q) :- !, body_pred(B, Q).

%   background_text(+M, +Clause, +Where, -Text): a DC clause as it was read
%   (its time-indexed terms and variable names back); a Prolog rule whose
%   body reads the data as a derived DC clause.
background_text(M, (H :- B), _, Text) :- !,
    (   reads_data(M, B)
    ->  internal_body_dc(M, B, DB), dc_term(M, H, DH),
        clause_text_vars((DH := DB), Text)
    ;   clause_text_vars((H :- B), Text)
    ).
background_text(M, C, W, Text) :-
    (   M:'$ddcl_named'(W, T-Vs) -> true ; T = C, Vs = [] ),
    undo_time(M, T, DC),
    learn_clause_text(M, clause(DC, Vs), Text).

%   undo_time(+M, +Term, -DC): every time-indexed term renamed for learning
%   (pos_t(A)) as it was written (pos(A):t).
undo_time(_, V, V) :- var(V), !.
undo_time(M, T0, T) :-
    compound(T0), !,
    compound_name_arguments(T0, N, As0),
    maplist(undo_time(M), As0, As),
    compound_name_arguments(T1, N, As),
    (   M:'$ddcl_timed'(N, _, _) -> dc_term(M, T1, T) ; T = T1 ).
undo_time(M, A, T) :-
    atom(A), M:'$ddcl_timed'(A, _, _), !, dc_term(M, A, T).
undo_time(_, T, T).

reads_data(M, B) :-
    body_pred(B, N/A),
    (   learn_data_pred(M, N, A, atom) -> true
    ;   A > 0, A1 is A-1, learn_data_pred(M, N, A1, rv(_))
    ), !.

internal_body_dc(M, (A, B), (DA, DB)) :- !, internal_body_dc(M, A, DA), internal_body_dc(M, B, DB).
internal_body_dc(M, (A ; B), (DA ; DB)) :- !, internal_body_dc(M, A, DA), internal_body_dc(M, B, DB).
internal_body_dc(M, (A -> B), (DA -> DB)) :- !, internal_body_dc(M, A, DA), internal_body_dc(M, B, DB).
internal_body_dc(M, \+ A, \+ DA) :- !, internal_body_dc(M, A, DA).
internal_body_dc(M, findall(T, G, L), findall_forward(T, DG, L)) :- !, internal_body_dc(M, G, DG).
internal_body_dc(M, G, DG) :- callable(G), !, dc_literal(M, G, DG).
internal_body_dc(_, G, G).

                 /*******************************
                 *           PRINTING           *
                 *******************************/

%!  learn_clause_text(+Data, +Clause, -Text:string) is det.
%
%   Clause (from learn_clause/5) as DC source text: the head and its
%   distribution on the first line, one body literal per line.
learn_clause_text(_, clause(C, Bs), Text) :-
    copy_term(C-Bs, C1-Bs1),
    maplist([Name=V]>>( var(V) -> V = '$VAR'(Name) ; true ), Bs1),
    term_variables(C1, Rest),
    maplist(=('$VAR'('_')), Rest),
    with_output_to(string(Text), print_clause(C1)).

clause_text_vars(C, Text) :-
    copy_term(C, C1),
    numbervars(C1, 0, _),
    with_output_to(string(Text), print_clause(C1)).

term_text(T, Bs, Text) :-
    copy_term(T-Bs, T1-Bs1),
    maplist([Name=V]>>( var(V) -> V = '$VAR'(Name) ; true ), Bs1),
    term_variables(T1, Rest),
    maplist(=('$VAR'('_')), Rest),
    with_output_to(string(Text), print_literal(T1)).

print_clause((H ~ D := B)) :- !,
    print_literal(H), write(' ~ '), print_term_(D),
    (   B == true -> write('.')
    ;   write(' :='), print_body(B), write('.')
    ).
print_clause((H := B)) :- !,
    print_literal(H), write(' :='), print_body(B), write('.').
print_clause((H :- B)) :- !,
    print_term_(H), write(' :-'), print_body(B), write('.').
print_clause(C) :-
    print_term_(C), write('.').

print_body(B) :-
    conj_to_list(B, Ls),
    foldl([L, Sep0, ',']>>( write(Sep0), nl, write('    '), print_literal(L) ), Ls, '', _).

conj_to_list((A, B), Ls) :- !, conj_to_list(A, LA), conj_to_list(B, LB), append(LA, LB, Ls).
conj_to_list(A, [A]).

print_literal(\+ G) :- !, write('\\+ '), print_inner(G).
print_literal((A -> B)) :- !, write('('), print_literal(A), write(' -> '), print_literal(B), write(')').
print_literal((A, B)) :- !, write('('), print_conj((A, B)), write(')').
print_literal(findall_forward(T, G, L)) :- !,
    write('findall_forward('), print_term_(T), write(', '),
    (   G = (_, _) -> write('('), print_conj(G), write(')') ; print_literal(G) ),
    write(', '), print_term_(L), write(')').
print_literal(G) :-
    compound(G), G =.. [Op, A, B], memberchk(Op, [~=, <, >, =<, >=, ==, is, =, =:=, =\=]), !,
    print_term_(A, 699), format(' ~w ', [Op]), print_term_(B, 699).
print_literal(G) :- print_term_(G).

print_inner(G) :-
    (   G = (_, _) -> write('('), print_conj(G), write(')')
    ;   G = (_ ~= _) -> print_literal(G)
    ;   print_literal(G)
    ).

print_conj((A, B)) :- !, print_literal(A), write(', '), print_conj(B).
print_conj(A) :- print_literal(A).

print_term_(T) :-
    print_term_(T, 1200).

print_term_(T, Priority) :-
    write_term(T, [quoted(true), numbervars(true), spacing(next_argument),
                   module(ddc_learn_data), priority(Priority)]).

                 /*******************************
                 *            NAMES             *
                 *******************************/

%   type_var_base(+Type, -Base): variables of type obj are Obj, Obj1, ...;
%   of DreaML's type la are La, ...; of an untyped argument X.
type_var_base(T, B) :-
    (   atom(T), T \== '_', T \== '' -> capitalise(T, B0), sanitise(B0, B)
    ;   B = 'X'
    ).

capitalise(A, C) :-
    atom_codes(A, [F|Rest]),
    code_type(U, to_upper(F)),
    atom_codes(C, [U|Rest]).

sanitise(A, S) :-
    atom_codes(A, Cs),
    include([C]>>( code_type(C, csym) ), Cs, Cs1),
    ( Cs1 == [] -> S = 'X' ; atom_codes(S, Cs1) ).

unique_name(Base, Used, Name) :-
    (   \+ memberchk(Base, Used) -> Name = Base
    ;   between(1, inf, I), atom_concat(Base, I, Name), \+ memberchk(Name, Used) -> true
    ).

%   clause_names(+Vars, +VarTerms, -Bindings): Name=Var for the node's
%   variables.
clause_names(Vars, Terms, Bs) :-
    length(Vars, N), length(Ts, N), append(Ts, _, Terms),
    maplist([v(Name, _), T, Name=T]>>true, Vars, Ts, Bs).

                 /*******************************
                 *       PROGRAM EVALUATION     *
                 *******************************/

%!  learn_program_scores(+Data, +ProgramFile, +Targets:list, +Options, -Scores:list(dict)) is det.
%
%   Score a DC program on the data: for each target (the internal names,
%   or [] for every random variable the program defines that has facts in
%   the data), every grounding in the data is scored by the first clause
%   of the program whose body holds in the data's world (the other facts
%   are its evidence): the log density (or mass) of the fact's value, the
%   prediction (the most probable value, or the mean).  Uncertain facts
%   give weighted partial worlds (expected scores).  Scores: one dict per
%   target with target, n (groundings), weight, log_likelihood (sum),
%   mean_log_likelihood, uncovered (groundings no clause applied to),
%   accuracy (discrete targets) or rmse (continuous).
%
%   @error ddc_learn(value_not_in_program(Key, Value, Values), File:Line)
learn_program_scores(M, File, Targets0, _Options, Scores) :-
    data_read_terms(File, own, Items),
    load_program(M, Items, Heads),
    (   Targets0 == []
    ->  findall(N, ( member(N/A, Heads), M:'$ddcl_pred'(N, A, rv(_)),
                     target_examples(M, N, A, Ks), Ks \== [] ), Targets)
    ;   Targets = Targets0
    ),
    maplist(target_scores(M, File), Targets, Scores).

load_program(M, Items0, Heads) :-
    maplist(internal_item(M), Items0, Items),
    dynamic(M:'$prog_clause'/3),
    retractall(M:'$prog_clause'(_, _, _)),
    forall(member(item(T, _, _, W), Items), program_item(M, T, W)),
    findall(N/A, M:'$prog_clause'(N/A, _, _), Hs0),
    sort(Hs0, Heads).

internal_item(M, item(T0, Vs, D, W), item(T, Vs, D, W)) :-
    internal_key(M, T0, T).

program_item(_, (:- _), _) :- !.
program_item(M, (K ~ D := B), W) :- !, program_rv(M, K, D, B, W).
program_item(M, (K ~ D <- B), W) :- !, program_rv(M, K, D, B, W).
program_item(M, (K ~ D), W) :- !, program_rv(M, K, D, true, W).
program_item(M, (H := B), W) :- !,
    (   callable(H), functor(H, N, A), \+ defined_in_data(M, N, A)
    ->  dc_goal(M, B, G, W), functor(H, HN, HA), dynamic(M:HN/HA), assertz(M:(H :- G))
    ;   true
    ).
program_item(M, C, _) :-
    ( C = (H :- _) -> true ; H = C ),
    (   callable(H), functor(H, N, A), \+ defined_in_data(M, N, A),
        \+ predicate_property(system:H, defined)
    ->  dynamic(M:N/A), assertz(M:C)
    ;   true
    ).

defined_in_data(M, N, A) :-
    functor(H, N, A),
    (   predicate_property(M:H, number_of_clauses(C)), C > 0 -> true
    ;   M:'$ddcl_background'(H0, _, _), \+ H0 \= H
    ).

program_rv(M, K, D, B, W) :-
    (   callable(K) -> true ; throw(error(ddc_learn(not_callable(K), W), _)) ),
    K =.. [N|Ks], length(Ks, A),
    dc_goal(M, B, G, W),
    assertz(M:'$prog_clause'(N/A, Ks-D-W, G)).

target_scores(M, File, N, _{target: Text, predicate: N, n: NE, weight: SW, log_likelihood: LL,
                           mean_log_likelihood: MLL, uncovered: U, accuracy: Acc, rmse: RMSE}) :-
    (   M:'$ddcl_pred'(N, A, rv(Spec)) -> true
    ;   throw(error(ddc_learn(target_without_facts(N/any), File:0), _))
    ),
    length(Vs, A), K0 =.. [N|Vs], dc_term(M, K0, T0), term_text(T0, [], Text),
    target_examples(M, N, A, Keys),
    length(Keys, NE),
    length(Ks, A), append(Ks, [V], As), TG =.. [N|As],
    (   M:'$ddcl_examples'(N/A, _, _, _) -> Missing = false ; Missing = '$none' ),
    Goal = ( ( once(M:TG) -> Y = V ; Y = Missing ),
             ( M:'$prog_clause'(N/A, Ks-D0-CW, G), once(M:G)
             ->  ddc_learn_data:eval_dist_at(D0, CW, D), R = d(D)
             ;   R = uncovered
             ) ),
    foldl(score_example(M, N, Ks, Goal, Y-R, Spec), Keys, s(0, 0, 0, 0, 0), S),
    S = s(SW, SLL, SC, SE, U),
    (   SW > 0, U =:= 0 -> MLL is SLL / SW ; SW > 0 -> MLL = -inf ; MLL = nan ),
    LL = SLL,
    (   Spec = discrete(_)
    ->  ( SW > 0 -> Acc is SC / SW ; Acc = nan ), RMSE = nan
    ;   Acc = nan, ( SW > 0 -> RMSE is sqrt(SE / SW) ; RMSE = nan )
    ).

score_example(M, N, Ks, Goal, Out, Spec, Key, S0, S) :-
    copy_term(Ks-Goal-Out, Key-G-O),
    empty_assoc(E0),
    K =.. [N|Key], example_weight(M, K, W),
    alts(M, G, O, E0, W, Alts),
    foldl(score_alt(M, N, Key, Spec), Alts, S0, S).

score_alt(M, N, Key, Spec, a(Y-R, _, F, _), s(W0, L0, C0, E0, U0), s(W, L, C, E, U)) :-
    W is W0 + F,
    (   R = d(D)
    ->  K =.. [N|Key],
        check_program_value(M, K, Y, D),
        dist_log_density(D, Y, LP),
        (   LP =:= -inf -> L is -inf ; L is L0 + F*LP ),
        (   Spec = discrete(_)
        ->  ( predicted(D, P), same_value(P, Y) -> C is C0 + F ; C = C0 ), E = E0
        ;   dist_mean(D, Mu), E is E0 + F*(Mu - Y)**2, C = C0
        ),
        U = U0
    ;   L = L0, C = C0, E = E0, U is U0 + 1
    ).

check_program_value(M, Key, Y, D) :-
    (   dist_support(D, Ps)
    ->  (   member(_-V, Ps), same_value(V, Y) -> true
        ;   dist_discrete(D), D = finite(PVs), \+ memberchk(_:Y, PVs)
        ->  findall(V, member(_:V, PVs), Vs),
            dc_term(M, Key, DK),
            ( fact_where(M, Key, W) -> true ; W = data ),
            throw(error(ddc_learn(value_not_in_program(DK, Y, Vs), W), _))
        ;   true
        )
    ;   true
    ).

predicted(D, V) :-
    dist_support(D, Ps),
    foldl([P-X, P0-X0, B]>>( P > P0 -> B = P-X ; B = P0-X0 ), Ps, -1-none, _-V).

same_value(A, B) :- number(A), number(B), !, A =:= B.
same_value(A, B) :- A == B.
