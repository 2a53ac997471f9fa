/*  ddc_learn_candidates.pl -- the literals the declarative bias allows at a
    node of a tree, and each branch's literal in DC syntax.
*/

:- module(ddc_learn_candidates,
          [ learn_candidates/3,         % +Data, +Node, -Candidates
            allowed_by_rank/4,          % +Data, +Target, +Cond, +Literal
            literal_preds/2,            % +Literal, -Names
            candidate_id/3,             % +Data, +Spec, -Id
            next_id/3,                  % +Data, +Kind, -Id
            branch_count/2,             % +Spec, -Branches
            node_branch_literal/8,      % +Data, +Spec, +VarTerms, +Branch, -Bound, -Literal,
                                        % +Names0, -Names
            dc_literal/3,               % +Data, +Internal, -DC
            fresh_values/2,             % +Fresh, -Vars
            agg_call/4                  % ?Aggregate, ?List, ?Result, ?Goal
          ]).

:- use_module(library(lists)).
:- use_module(library(apply)).
:- use_module(ddc_learn_data).
:- use_module(ddc_learn_records).
:- use_module(ddc_learn_text, [capitalise/2, clause_names/3, term_text/3, type_var_base/2,
                               unique_name/3]).

:- set_prolog_flag(optimise, true).

/** <module> Candidate literals of the structure learner

A candidate is an instance of a mode of the target (its + arguments bound
to the node's variables, its constants chosen), stored in the data
module as '$ddcl_cand'(Id, Key, Spec) under one id per distinct instance.
Spec is a candidate record (ddc_learn_records.pl); its kind decides its
branches (the table in ddc/learn.pl).
node_branch_literal/8 writes a branch as the body literal of a learned clause.
*/

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
    node_info_target(Info, target(TN, TA, _)),
    node_info_vars(Info, Vars),
    node_info_used(Info, Used),
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

%!  allowed_by_rank(+Data, +Target:atom, +Cond, +Lit) is semidet.
%
%   Every predicate the literal (and its condition) reads ranks below the
%   target (unranked predicates rank 0, always allowed), and none is the
%   target itself.
allowed_by_rank(M, T, C, L) :-
    literal_preds((C, L), Ps),
    \+ memberchk(T, Ps),
    ( M:'$ddcl_rank'(T, RT) -> true ; RT = 0 ),
    forall(member(P, Ps), ( M:'$ddcl_rank'(P, RP) -> RP < RT ; true )).

%!  literal_preds(+Literal, -Names:list(atom)) is det.
%
%   The predicate names a mode's literal (none, or a conjunction) reads.
literal_preds(none, []) :- !.
literal_preds((A, B), Ps) :- !,
    literal_preds(A, PA), literal_preds(B, PB), append(PA, PB, Ps).
literal_preds(L, [N]) :- functor(L, N, _).

%   instance(+M, +Vars, +MId, +Agg, +Cond, +Lit, +Where, -Spec) is nondet.
%
%   Spec is a candidate record (its fields: ddc_learn_records.pl).
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
    make_candidate([mode(MId), kind(Kind), goal(G), inputs(Ins), fresh(Fresh), value(Val),
                    domain(Dom), thresholds(Ts), aggregate(none), literal(lit(true, G, []))],
                   Spec).
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
    make_candidate([mode(MId), kind(Kind), goal(G), inputs(Ins), fresh([]), value(Val),
                    domain(Dom), thresholds([]), aggregate(Agg), literal(lit(CG, LG, Locals))],
                   Spec).

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

%!  candidate_id(+Data, +Spec, -Id:integer) is det.
%
%   The id of a candidate: one per distinct instance, assigned the first
%   time it is seen.
candidate_id(M, Spec, Id) :-
    instance_key(Spec, Key),
    (   M:'$ddcl_cand'(Id0, Key, _) -> Id = Id0
    ;   next_id(M, candidate, Id),
        assertz(M:'$ddcl_cand'(Id, Key, Spec))
    ).

instance_key(Spec, k(MId, G1)) :-
    candidate_mode(Spec, MId),
    candidate_goal(Spec, G),
    candidate_inputs(Spec, Ins),
    copy_term(G-Ins, G1-Ins1),
    maplist([P-'$in'(P)]>>true, Ins1),
    numbervars(G1, 0, _).

%!  next_id(+Data, +Kind:atom, -Id:integer) is det.
%
%   The next id of a counter of the data module (node, candidate), from 1.
next_id(M, Kind, Id) :-
    (   retract(M:'$ddcl_counter'(Kind, Id0)) -> Id is Id0+1 ; Id = 1 ),
    assertz(M:'$ddcl_counter'(Kind, Id)).

candidate_dict(M, Vars, NV, TA, Id, _{id: Id, mode: MId, kind: Kind, branches: NB, labels: Labels,
                                      regressor: Regs, root: Root, fresh: Fresh, where: Where}) :-
    M:'$ddcl_cand'(Id, _, Spec),
    candidate_mode(Spec, MId),
    candidate_kind(Spec, Kind),
    candidate_inputs(Spec, Ins),
    candidate_fresh(Spec, F),
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

%!  branch_count(+Spec, -Branches:integer) is det.
%
%   The number of outcomes of a candidate (the table in ddc/learn.pl).
branch_count(Spec, N) :-
    candidate_kind(Spec, Kind),
    kind_branch_count(Kind, Spec, N).

kind_branch_count(discrete, Spec, N) :- !,
    candidate_domain(Spec, D), length(D, K), N is K+1.
kind_branch_count(agg_discrete, Spec, N) :- !,
    candidate_domain(Spec, D), length(D, K), N is K+1.
kind_branch_count(threshold, Spec, N) :- !,
    candidate_thresholds(Spec, Ts), length(Ts, K), N is K+2.
kind_branch_count(count, _, 1) :- !.
kind_branch_count(_, _, 2).

branch_regressor(numeric, 0, true) :- !.
branch_regressor(count, 0, true) :- !.
branch_regressor(agg_numeric, 0, true) :- !.
branch_regressor(_, _, false).

branch_label(M, Spec, VarTerms, Bs0, B, Text) :-
    node_branch_literal(M, Spec, VarTerms, B, _, Lit, Bs0, Bs),
    term_text(Lit, Bs, Text).

%!  node_branch_literal(+Data, +Spec, +VarTerms:list, +Branch:integer, -Bound,
%!                      -Literal, +Names0:list, -Names:list) is det.
%
%   The body literal of a candidate's branch (branch_literal/6) at a node
%   whose variables are the terms VarTerms: Bound is a copy of Spec with
%   its inputs bound to them; Names0 gains names for its new variables.
node_branch_literal(M, Spec, VarTerms, B, S1, Lit, Bs0, Bs) :-
    copy_term(Spec, S1),
    candidate_inputs(S1, Ins),
    candidate_fresh(S1, Fresh),
    maplist(bind_in(VarTerms), Ins),
    fresh_names(Fresh, Bs0, Bs1),
    branch_literal(M, S1, B, Lit, Bs1, Bs).

%   bind_in(+VarTerms, +Input): Input P-V: V is the node's variable at
%   position P of VarTerms.
bind_in(VarTerms, P-V) :- nth0(P, VarTerms, V).

%!  fresh_values(+Fresh:list, -Vars:list) is det.
%
%   The variables of [v(Type, Var)], shared (findall/3 would copy them).
fresh_values([], []).
fresh_values([v(_, V)|Fs], [V|Vs]) :- fresh_values(Fs, Vs).

%   fresh_names(+Fresh, +Names0, -Names): names (Name=Var) for the unbound
%   variables of Fresh ([v(Type, Var)]), after their type (type_var_base/2),
%   unique among Names0.
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

%   branch_literal(+Data, +Spec, +Branch, -Literal, +Names0, -Names): the
%   body literal of a candidate's branch in DC syntax; names for its new
%   variables added to Names0.
branch_literal(M, Spec, B, Lit, Bs0, Bs) :-
    candidate_kind(Spec, Kind),
    candidate_goal(Spec, G),
    candidate_fresh(Spec, Fresh),
    candidate_value(Spec, Val),
    candidate_domain(Spec, Dom),
    candidate_thresholds(Spec, Ts),
    candidate_aggregate(Spec, Agg),
    candidate_literal(Spec, lit(CG, LG, Locals)),
    fresh_names(Locals, Bs0, Bs00),
    value_name(M, Kind, Agg, LG, Val, Bs00, Bs1),
    dc_literal(M, G, DG),
    kind_branch_literal(Kind, B, DG, Fresh, Val, Dom, Ts, Agg, CG, LG, M, Lit, Bs1, Bs).

kind_branch_literal(discrete, B, K ~= V, _, V, Dom, _, _, _, _, _, Lit, Bs, Bs) :-
    (   nth0(B, Dom, C) -> V = C, Lit = (K ~= V) ; Lit = (\+ K ~= _) ).
kind_branch_literal(numeric, B, K ~= V, _, V, _, _, _, _, _, _, Lit, Bs, Bs) :-
    (   B =:= 0 -> Lit = (K ~= V) ; Lit = (\+ K ~= _) ).
kind_branch_literal(threshold, B, K ~= V, _, V, _, Ts, _, _, _, _, Lit, Bs, Bs) :-
    length(Ts, NT),
    (   B =:= 0 -> Ts = [T|_], Lit = (K ~= V, V < T)
    ;   B =:= NT -> last(Ts, T), Lit = (K ~= V, V >= T)
    ;   B < NT -> B0 is B-1, nth0(B0, Ts, T0), nth0(B, Ts, T1), Lit = (K ~= V, V >= T0, V < T1)
    ;   Lit = (\+ K ~= _)
    ).
kind_branch_literal(test, B, DG, Fresh, _, _, _, _, _, _, _, Lit, Bs, Bs) :-
    (   B =:= 0 -> ( Fresh == [] -> Lit = DG ; Lit = (DG -> true) )
    ;   Lit = (\+ DG)
    ).
kind_branch_literal(count, _, _, _, _, _, _, _, CG, LG, M, Lit, Bs0, Bs) :-
    agg_goal(M, CG, LG, DG),
    list_var(Bs0, Bs1, L),
    count_var(M, LG, Bs1, Bs, X),
    Lit = (findall_forward(x, DG, L), length(L, X)).
kind_branch_literal(agg_numeric, B, _, _, V, _, _, Agg, CG, LG, M, Lit, Bs0, Bs) :-
    agg_goal(M, CG, LG, DG),
    list_var(Bs0, Bs1, L),
    (   B =:= 0
    ->  agg_call(Agg, L, X, Call), agg_result_var(M, Agg, LG, Bs1, Bs, X),
        Lit = (findall_forward(V, DG, L), Call)
    ;   Bs = Bs1, Lit = (findall_forward(V, DG, L), L == [])
    ).
kind_branch_literal(agg_discrete, B, _, _, V, Dom, _, Agg, CG, LG, M, Lit, Bs0, Bs) :-
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

%!  agg_call(?Aggregate:atom, ?List, ?Result, ?Goal) is nondet.
%
%   Goal computes Result, the aggregate of List (mean_list(List, Result),
%   ...).
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

%!  dc_literal(+Data, +Internal, -DC) is det.
%
%   An internal literal (a conjunction of them) in DC syntax: a random
%   variable's p_t(K, V) is p(K):t ~= V.
dc_literal(M, (A, B), (DA, DB)) :- !, dc_literal(M, A, DA), dc_literal(M, B, DB).
dc_literal(M, G, DG) :-
    G =.. [N|As],
    length(As, Ar),
    (   Ar > 0, A is Ar-1, learn_data_pred(M, N, A, rv(_))
    ->  append(Ks, [V], As), K =.. [N|Ks], dc_term(M, K, DK), DG = (DK ~= V)
    ;   dc_term(M, G, DG)
    ).
