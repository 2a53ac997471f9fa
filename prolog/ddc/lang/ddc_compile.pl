/*  ddc_compile.pl -- compiling DC programs into Prolog clauses.

    Part of the DDC system (ddc.pl is the module users load).  Turns a
    program's items (ddc_read.pl) into the clauses of its module: one
    '$rv'/9 clause per random variable clause, one clause per derived
    clause with a dispatcher per derived predicate, the sweep's tables and
    the clauses' file positions.  Bodies are compiled by ddc_body.pl.
*/

:- module(ddc_compile,
          [ compile_program/5           % +File, +Module, +Terms, -Clauses, -Info
          ]).

:- use_module(library(lists)).
:- use_module(library(apply)).
:- use_module(library(pairs)).
:- use_module(library(assoc)).
:- use_module(library(ordsets)).
:- use_module(library(modules)).
:- use_module(ddc_records).
:- use_module(ddc_dist).
:- use_module(ddc_read).
:- use_module(ddc_body).
:- use_module('../runtime/ddc_world', [needs_eval/1, eval_dist/2, world_time_goal/3]).

:- use_module(ddc_ops).

%   Arithmetic compiled to virtual-machine instructions (local to this
%   file; see ddc.pl).
:- set_prolog_flag(optimise, true).

/** <module> Compiling DC programs

The clauses a program module gets (besides its plain Prolog clauses):

  - '$rv'(X, T, W, Skip, Ev, Out, Tier, Id, Rivals): random variable X at
    time T (u: untimed) in world W is defined by clause Id (> Skip) of
    Tier (1: untimed, h:0, h:t+1; 2: the h:t fallback), with Out its
    distribution (or, for evidence Ev = ev(V) on a val/1 clause inverted,
    '$prop'(LogJacobian)); Rivals: whether a later clause may define X too.
  - the derived predicates' clauses and dispatchers (derived_name/3).
  - '$sweep'/4 and '$sweep_key'/4: what a filter's sweep goes through.
  - '$rv_pos'(Id, File, Line) and '$ddc_items'(Items) (program_items/2).
*/

%!  compile_program(+File, +Module, +Terms, -Clauses, -Info) is det.
%
%   Clauses are the clauses of the program read from File (Terms, as
%   ddc_read:read_program/2 gives them) for Module, Info its info record
%   (ddc_body.pl).  Errors name File:Line.
compile_program(File, M, Terms, Clauses, Info) :-
    reset_undefined,
    classify_program(File, M, Terms, Items, Opts, DirClauses),
    program_info(Items, Opts, Info),
    %   '$rv' clauses: tier 1 (untimed, h:0, h:t+1) before tier 2 (h:t)
    rivals_table(Items, Info, RivalsOf),
    findall(C, ( member(I, Items), \+ state_rv(I), compile_item_at(I, File, Info, RivalsOf, C) ), Cs1),
    findall(C, ( member(I, Items), state_rv(I), compile_item_at(I, File, Info, RivalsOf, C) ), Cs2),
    append(Cs1, Cs2, Cs0),
    derived_dispatchers(M, Info, Ds),
    clause_positions(Items, File, Ps),
    findall(Id-K-C, ( member(rv(Id, X, K, _, B, _), Items), K \== u, K \== state,
                      sweep_key_clause(Id, X, K, B, Info, C) ), SwKs0),
    distinct_sweep_keys(SwKs0, SwKs),
    findall('$sweep'(rv, K, X, Id),
            ( member(Id-K-C, SwKs), C = ('$sweep_key'(_, X, _, _) :- _) ), Sw1a),
    findall(C, member(_-_-C, SwKs), Sw1b),
    append(Sw1a, Sw1b, Sw1),
    info_impure(Info, Impure),
    %   '$sweep'(der, Kind, N/A, sw(Shared, When, G, Call, T, W)): Call (the
    %   h:t+1 clauses of derived predicate N/A) gives the instances G at T
    %   in W; When is eager (materialised by the sweep: the program reads
    %   N/A at a time other than t+1) or lazy (on first demand, '$mat'/3)
    findall(K-N/A, ( member(der(_, X, K, _, _), Items), K \== u, K \== state,
                     functor(X, N, A) ), DKs0),
    sort(DKs0, DKs),
    lookback_preds(Items, Back),
    findall('$sweep'(der, K, N/A, sw(Sh, When, G, H1, T, W)),
            ( member(K-N/A, DKs),
              ( memberchk(clean(t/N/A), Impure) -> Sh = shared ; Sh = 0 ),
              ( memberchk(N/A, Back) -> When = eager ; When = lazy ),
              functor(G, N, A), G =.. [_|Args],
              derived_name(N, dt1, DN1), append(Args, [T, W], CArgs), H1 =.. [DN1|CArgs] ),
            Sw2a),
    sort(Sw2a, Sw2),
    findall(rivals(Id, R), ( member(rv(Id, _, _, _, _, _), Items), rivals(Id, RivalsOf, R) ), Rivals),
    append(Items, Rivals, BatchItems),
    append([DirClauses, Cs0, Ds, Ps, Sw1, Sw2, ['$ddc_items'(BatchItems)]], Clauses),
    b_setval(ddc_compiling, []),
    warn_undefined.

state_rv(rv(_, _, state, _, _, _)).

%   lookback_preds(+Items, -Preds): the N/A read in some body at a time
%   other than t+1 (t, t-K, a number, a variable, current/prior), i.e.
%   possibly at a frozen time by the program itself.
lookback_preds(Items, Preds) :-
    findall(N/A, ( member(I, Items),
                   ( I = rv(_, _, _, _, B, _) ; I = der(_, _, _, B, _) ),
                   time_ref(B, X, TE), \+ next_time(TE),
                   callable(X), functor(X, N, A) ), L),
    sort(L, Preds).

next_time(TE) :- nonvar(TE), TE = T0+K, T0 == t, K == 1.

time_ref(V, _, _) :- var(V), !, fail.
time_ref((X0:T0)+K, X, TE) :- T0 == t, integer(K), !, X = X0, TE = t+K.
time_ref((X0:T0)-K, X, TE) :- T0 == t, integer(K), !, X = X0, TE = t-K.
time_ref(X0:TE0, X, TE) :- !, X = X0, TE = TE0.
time_ref(current(X0), X, t) :- !, X = X0.
time_ref(prior(X0), X, 0) :- !, X = X0.
time_ref(T, X, TE) :- compound(T), arg(_, T, A), time_ref(A, X, TE).


%   program_info(+Items, +Opts, -Info): the program's info record
%   (ddc_body.pl).
program_info(Items, Opts, info(DerU, DerT, RvU, RvT, Plain, Impure, First)) :-
    findall(N/A, ( member(der(_, X, u, _, _), Items), functor(X, N, A) ), DU), sort(DU, DerU),
    findall(N/A, ( member(der(_, X, K, _, _), Items), K \== u, functor(X, N, A) ), DT), sort(DT, DerT),
    findall(N/A, ( member(rv(_, X, u, _, _, _), Items), functor(X, N, A) ), RU), sort(RU, RvU),
    findall(N/A, ( member(rv(_, X, K, _, _, _), Items), K \== u, functor(X, N, A) ), RT), sort(RT, RvT),
    findall(N/A, ( member(plain(C, _), Items), clause_head(C, H), functor(H, N, A) ), P0),
    findall(N/A, ( member(plain(builtin(P), _), Items), callable(P), functor(P, N, A) ), P1),
    append(P0, P1, P2), sort(P2, Plain),
    findall(S, ( member(first(Spec), Opts), spec_list(Spec, Ss), member(S, Ss) ), First),
    impure_preds(Items, Impure0),
    append(RvU, RvT, Rvs),
    clean_preds(Items, Rvs, Clean),
    findall(fact(S), ( member(facts(Spec), Opts), spec_list(Spec, Ss), member(S, Ss) ), Facts),
    append([Impure0, Clean, Facts], Impure).

clause_head((H :- _), H) :- !.
clause_head(H, H).

%   Derived predicates whose proof draws fresh randomness (true/1,
%   sample/2), directly or through other derived predicates: memoised.
impure_preds(Items, Impure) :-
    findall(K-Calls,
            ( member(der(_, X, Kind, B, _), Items),
              functor(X, N, A), tkind(Kind, TK), K = TK/N/A,
              body_calls(B, Calls) ),
            Edges),
    findall(K, ( member(K-Cs, Edges), memberchk(random, Cs) ), Seed0),
    sort(Seed0, Seed),
    callers_closure(Seed, Edges, Impure).

%   Derived predicates whose truth depends only on the facts asserted into
%   the world (and on plain Prolog, parameters, other such predicates):
%   no random variable is read, nothing random is drawn.  Listed in the
%   impure field of the info record as clean(u/N/A) or clean(t/N/A).  All particles
%   of a filter step hold the same facts, so their answers are computed
%   once per step and shared ('$shared'/3).  Conservative: any doubt
%   (a variable goal, call/N, a random builtin, a term that names a random
%   variable) makes a predicate particle-dependent.
clean_preds(Items, Rvs, Clean) :-
    sort(Rvs, RvSet),
    pairs_keys_values(RvPairs, RvSet, RvSet),
    list_to_assoc(RvPairs, RvIndex),
    findall(K-Dirty-Calls,
            ( member(der(_, X, Kind, B, _), Items),
              functor(X, N, A), tkind(Kind, TK), K = TK/N/A,
              body_calls(B, Calls),
              ( body_dirty(B, RvIndex) -> Dirty = true ; Dirty = false ) ),
            Edges),
    findall(K, member(K-_-_, Edges), Ks0), sort(Ks0, Ks),
    findall(K, member(K-true-_, Edges), D0), sort(D0, Dirty0),
    findall(K-Calls, member(K-_-Calls, Edges), CallEdges),
    callers_closure(Dirty0, CallEdges, Dirty),
    ord_subtract(Ks, Dirty, CleanKs),
    findall(clean(K), member(K, CleanKs), Clean0),
    %   clean untimed predicates defined by unit clauses only (`object(o1)
    %   := true.`): a first-argument indexed lookup is cheaper than the
    %   shared table, so they are called directly (der_dispatch_u/5)
    findall(u/N/A, ( member(der(_, X, Kind, B, _), Items), tkind(Kind, u), B \== true,
                     functor(X, N, A) ), NonUnit0),
    sort(NonUnit0, NonUnit),
    ord_subtract(CleanKs, NonUnit, UnitKs),
    findall(unit(K), ( member(K, UnitKs), K = u/_/_ ), Units),
    append(Clean0, Units, Clean).

%   callers_closure(+Seeds, +Edges, -Closure): Closure (an ordered set) is
%   Seeds and every key K of Edges (K-Calls pairs, a key may have several)
%   that calls, directly or through other keys, a key of Seeds.  A search
%   from the seeds over the reversed calls, each key visited once.
callers_closure(Seeds, Edges, Closure) :-
    findall(C-K, ( member(K-Cs, Edges), member(C, Cs) ), Rev0),
    sort(Rev0, Rev),
    group_pairs_by_key(Rev, Callers),
    list_to_assoc(Callers, CallersOf),
    pairs_keys_values(SeedPairs, Seeds, Seeds),
    list_to_assoc(SeedPairs, Seen0),
    callers_visit(Seeds, CallersOf, Seen0, Seen),
    assoc_to_keys(Seen, Closure).

callers_visit([], _, Seen, Seen).
callers_visit([K|Ks], CallersOf, Seen0, Seen) :-
    (   get_assoc(K, CallersOf, Cs) -> true ; Cs = [] ),
    foldl(callers_new, Cs, Seen0-Ks, Seen1-Ks1),
    callers_visit(Ks1, CallersOf, Seen1, Seen).

callers_new(C, Seen0-Ks, Seen-Ks1) :-
    (   get_assoc(C, Seen0, _)
    ->  Seen = Seen0, Ks1 = Ks
    ;   put_assoc(C, Seen0, C, Seen), Ks1 = [C|Ks]
    ).

body_dirty(B, _) :- body_call(B, '$var'), !.
body_dirty(B, _) :- body_call(B, u/N/_), ( N == call ; sub_atom(N, _, _, _, random) ), !.
body_dirty(B, RvIndex) :-
    sub_term(S, B), nonvar(S),
    (   S = (_ ~= _)
    ;   S = true(_)
    ;   S = sample(_, _)
    ;   S = X:_, nonvar(X), callable(X), functor(X, N, A), get_assoc(N/A, RvIndex, _)
    ;   callable(S), functor(S, N, A), get_assoc(N/A, RvIndex, _)
    ), !.

tkind(u, u) :- !.
tkind(_, t).

body_calls(B, Calls) :-
    findall(C, body_call(B, C), Calls).

body_call(V, '$var') :- var(V), !.
body_call((A,B), C) :- !, ( body_call(A, C) ; body_call(B, C) ).
body_call((A;B), C) :- !, ( body_call(A, C) ; body_call(B, C) ).
body_call((A->B), C) :- !, ( body_call(A, C) ; body_call(B, C) ).
body_call((A*->B), C) :- !, ( body_call(A, C) ; body_call(B, C) ).
body_call(\+ A, C) :- !, body_call(A, C).
body_call(findall(_, G, _), C) :- !, body_call(G, C).
body_call(findall_forward(_, G, _), C) :- !, body_call(G, C).
body_call(forall(A, B), C) :- !, ( body_call(A, C) ; body_call(B, C) ).
body_call(once(A), C) :- !, body_call(A, C).
body_call(true(_), random) :- !.
body_call(sample(_, _), random) :- !.
body_call(_ ~= _, _) :- !, fail.
body_call(X:_, t/N/A) :- callable(X), !, functor(X, N, A).
body_call((X:_)+_, t/N/A) :- callable(X), !, functor(X, N, A).
body_call(G, u/N/A) :- callable(G), functor(G, N, A).

clause_positions(Items, File, Ps) :-
    findall('$rv_pos'(Id, File, L),
            ( member(I, Items), item_id(I, Id), item_line(I, L) ), Ps).


%   compile_item_at(+Item, +File, +Info, +RivalsOf, -Clause) is nondet.
%
%   compile_item/5, with any error of compiling or checking the item (an
%   atom where arithmetic needs a function, a plain clause for a control
%   construct or a built-in predicate, `observed()`) the program's error at
%   the item's line.
compile_item_at(I, File, Info, RivalsOf, '$at'(Line, C)) :-
    item_where(I, File, Where),
    Where = _:Line,
    b_setval(ddc_compiling, Where),
    catch(compile_item(I, File, Info, RivalsOf, C), E, item_error(E, I, File)),
    check_clause(C, I, Where).

item_error(E, I, File) :-
    item_where(I, File, Where),
    load_error(E, I, Where).

item_where(plain(_, L), File, File:L) :- !.
item_where(I, File, File:L) :- item_line(I, L), !.
item_where(_, File, File:0).

%   check_clause(+Clause, +Item, +Where): the errors assertz/1 would raise
%   when the program is installed, found before anything is replaced: a
%   head that is a control construct or a system predicate, and arithmetic
%   (compiled inline) on an atom that is not an arithmetic function.
check_clause(C, I, Where) :-
    (   C = (H :- B) -> true ; H = C, B = true ),
    (   var(H)
    ->  true
    ;   ( \+ callable(H) ; timed_plain_head(H) )
    ->  throw(error(ddc(bad_head(H), Where), _))
    ;   predicate_property(system:H, iso)
    ->  functor(H, N, A),
        load_error(error(permission_error(modify, static_procedure, N/A), _), I, Where)
    ;   arithmetic_atom(B, Atom)
    ->  load_error(error(type_error(evaluable, Atom/0), _), I, Where)
    ;   term_variables(H, Seen),
        \+ fresh_arithmetic(B, Seen, _)
    ->  throw(error(ddc(fresh_arithmetic, Where), _))
    ;   true
    ).

%   fresh_arithmetic(+Body, +Seen0, -Seen) fails when an arithmetic goal
%   that the compiler inlines (is/2 or a comparison, in a conjunction,
%   disjunction, if-then-else or negation) reads a variable that occurs
%   nowhere before it in the clause: assertz/1 would refuse the clause.
fresh_arithmetic(G, Seen0, Seen) :-
    var(G), !, Seen = [G|Seen0].
fresh_arithmetic(G, Seen0, Seen) :-
    compound(G), compound_name_arity(G, Op, 2),
    memberchk(Op, [',', ;, ->, *->]), !,
    arg(1, G, A), arg(2, G, B),
    fresh_arithmetic(A, Seen0, Seen1),
    fresh_arithmetic(B, Seen1, Seen).
fresh_arithmetic(\+ G, Seen0, Seen) :- !,
    fresh_arithmetic(G, Seen0, Seen).
fresh_arithmetic(G, Seen0, Seen) :-
    compound(G), compound_name_arity(G, Op, 2),
    memberchk(Op, [is, <, >, =<, >=, =:=, =\=]), !,
    arg(2, G, R), arg(1, G, L),
    (   Op == is -> Read = R ; Read = L-R ),
    term_variables(Read, Vs),
    forall(member(V, Vs), memberchk_eq(V, Seen0)),
    term_variables(L, Ls),
    append(Ls, Seen0, Seen).
fresh_arithmetic(G, Seen0, Seen) :-
    term_variables(G, Vs),
    append(Vs, Seen0, Seen).

%   A plain clause whose head is a time-indexed term (`observed(a):t+1.`, a
%   line of data rather than of a program) is not a clause of the program.
timed_plain_head(H) :-
    (   H = _:_ -> true ; H = (X:_)+_, nonvar(X) -> true ; H = (X:_)-_, nonvar(X) ).

%   arithmetic_atom(+Body, -Atom): Atom appears where Body's arithmetic
%   (is/2 and the comparisons) needs a number and is not a function.
arithmetic_atom(B, Atom) :-
    sub_term(G, B), compound(G),
    compound_name_arity(G, Op, 2),
    memberchk(Op, [is, <, >, =<, >=, =:=, =\=]),
    arg(Side, G, Expr), ( Op == is -> Side == 2 ; true ),
    sub_term(Atom, Expr), atom(Atom), Atom \== [],
    \+ current_arithmetic_function(Atom), !.

%   compile_item(+Item, +File, +Info, +RivalsOf, -Clause) is nondet.
%   RivalsOf: rivals_table/3 of the program's items.
compile_item(plain(builtin(_), _), _, _, _, _) :- !, fail.
compile_item(plain(C, _), _, _, _, C).
compile_item(rv(Id, X, K, D, B, L), File, Info, RivalsOf, Clause) :-
    compile_rv(Id, X, K, D, B, L, File, Info, RivalsOf, Clause).
compile_item(der(Id, X, K, B, _), _, Info, _, Clause) :-
    compile_der(Id, X, K, B, Info, Clause).

%   '$rv'(X, T, W, Skip, Ev, Out, Tier, Id, Rivals)
compile_rv(Id, X, K, D0, B0, L, File, Info, RivalsOf, Clause) :-
    Head = '$rv'(X, TArg, W, Skip, Ev, Out, Tier, Id, Rivals),
    tier(K, Tier),
    rivals(Id, RivalsOf, Rivals),
    time_guard(K, TArg, W, Now, Guard),
    Ctx = ctx(W, Now, Info, clause),
    range_support(X, D0, B0, D, B),
    catch(compile_body(B, Ctx, BodyCode), E, clause_compile_error(E, File, L)),
    (   ground(X) -> GroundCheck = true
    ;   GroundCheck = ( ground(X) -> true ; ddc_world:'$clause_error'(W, Id, non_ground_head(X)) )
    ),
    dist_code(D, Id, File, L, Out0, DistCode),
    (   D = val(V), var(V),
        invert_val_body(B, V, Ctx, EvVal, LJ, InvCode)
    ->  Body = ( Id > Skip, Guard,
                 (   Ev == none
                 ->  BodyCode, GroundCheck, DistCode, Out = Out0
                 ;   Ev = ev(EvVal), InvCode, GroundCheck, Out = '$prop'(LJ)
                 ) )
    ;   Body = ( Id > Skip, Guard, BodyCode, GroundCheck, DistCode, Out = Out0 )
    ),
    drop_unused_time(Guard, Now, Body, Body1),
    Clause = (Head :- Body1).

%   range_support(+Head, +Dist, +Body, -Dist1, -Body1): a clause that builds
%   the list of integers Lo..Hi only to be the support of a uniform
%   (`x ~ uniform(L) := ..., findall(I, between(Lo, Hi, I), L).`) draws
%   from the range itself, uniform(Lo:Hi): the same value for the same random
%   state, and the mass of a value without building or scanning the list.
%   Only when L is used nowhere else.  (An empty range is the same error,
%   empty_support, shown as uniform(Lo:Hi) instead of uniform([]).)
range_support(X, uniform(L), B, uniform(Lo1:Hi1), B1) :-
    var(L), \+ occurs_in(L, X),
    conj_list(B, Ls),
    select(F, Ls, ddc_world:'$range_bounds'(Lo, Hi, Lo1, Hi1), Ls1),
    nonvar(F), F = findall(T, G, L2), L2 == L, var(T),
    nonvar(G), G = between(Lo, Hi, T1), T1 == T, \+ occurs_in(T, Lo-Hi),
    term_variables(Ls1, Vs), \+ memberchk_eq(L, Vs),
    !,
    conj_from_list(Ls1, B1).
range_support(_, D, B, D, B).


%   An untimed clause reads the world's time only if its body uses it.
drop_unused_time(Guard, Now, Body, Body1) :-
    (   world_time_goal(_, Now0, Guard), Now0 == Now,
        Body = (A, G, Rest), G == Guard,
        \+ occurs_in(Now, Rest)
    ->  Body1 = (A, Rest)
    ;   Body1 = Body
    ).

%   '$sweep_key'(Id, X, T, W): the candidate heads X of transition clause
%   Id at time T: the shortest prefix of its body that binds the head's
%   variables (the filter's sweep then reads each candidate, which picks
%   the clause that applies; running whole bodies there would be wasted).
%   distinct_sweep_keys(+Id-Kind-Clause, -Kept): the clauses of one random
%   variable often share the prefix that enumerates their heads
%   (`object(O)`): the sweep reads each key once, so a clause whose key
%   enumerator is a variant of an earlier one (same kind) is left out.
%   The keys kept so far are found by the variant hash of their kind and
%   shape (variant terms have the same hash), each candidate then compared
%   with =@=: linear in the number of clauses.
distinct_sweep_keys(SwKs, Kept) :-
    empty_assoc(Seen),
    distinct_sweep_keys(SwKs, Seen, Kept).

distinct_sweep_keys([], _, []).
distinct_sweep_keys([Id-K-C|T], Seen0, Kept) :-
    sweep_key_shape(C, S),
    variant_sha1(K-S, Hash),
    (   get_assoc(Hash, Seen0, Shapes) -> true ; Shapes = [] ),
    (   member(K0-S0, Shapes), K0-S0 =@= K-S
    ->  Kept = Kept1, Seen = Seen0
    ;   Kept = [Id-K-C|Kept1],
        put_assoc(Hash, Seen0, [K-S|Shapes], Seen)
    ),
    distinct_sweep_keys(T, Seen, Kept1).

sweep_key_shape(('$sweep_key'(_, X, T, W) :- B), s(X, T, W, B)).

sweep_key_clause(Id, X, K, B, Info, ('$sweep_key'(Id, X, TArg, W) :- Guard, Code)) :-
    time_guard(K, TArg, W, Now, Guard),
    sweep_prefix(X, B, PB),
    compile_body(PB, ctx(W, Now, Info, clause), Code).

sweep_prefix(X, B, PB) :-
    conj_list(B, Ls),
    term_variables(X, HVs),
    binding_prefix(Ls, HVs, Prefix),
    conj_from_list(Prefix, PB).

binding_prefix(_, [], []) :- !.
binding_prefix([], _, []).
binding_prefix([L|Ls], Vs, [L|P]) :-
    (   binds_nothing(L) -> Vs1 = Vs
    ;   term_variables(L, LVs), vars_not_in(Vs, LVs, Vs1)
    ),
    binding_prefix(Ls, Vs1, P).

binds_nothing(L) :- var(L), !, fail.
binds_nothing(\+ _).
binds_nothing(L) :- compound(L), functor(L, Op, 2), memberchk(Op, [<, >, =<, >=, =:=, =\=, \==, ==]).

vars_not_in([], _, []).
vars_not_in([V|Vs], LVs, Out) :-
    (   memberchk_eq(V, LVs) -> Out = Out1 ; Out = [V|Out1] ),
    vars_not_in(Vs, LVs, Out1).

memberchk_eq(X, L) :- nonvar(L), L = [Y|Ys], ( X == Y -> true ; memberchk_eq(X, Ys) ).

clause_compile_error(error(ddc(C, _), _), File, L) :- !,
    throw(error(ddc(C, File:L), _)).
clause_compile_error(E, _, _) :- throw(E).

tier(state, 2) :- !.
tier(_, 1).

time_guard(u, u, W, Now, Guard) :- world_time_goal(W, Now, Guard).
time_guard(state, Now, _, Now, integer(Now)).
time_guard(trans, T, W, Now, (integer(T), T >= 1, ddc_world:'$live'(W, T), Now is T-1)).
time_guard(persist, T, W, Now, (integer(T), T >= 1, ddc_world:'$live'(W, T), Now is T-1)).
time_guard(fixed(N), N, W, N, ddc_world:'$live'(W, N)).

%   rivals(+Id, +RivalsOf, -R): R is true if a later clause of the same
%   tier than random variable clause Id can define a variable that Id can
%   also define (their heads unify, their kinds of time overlap: the same
%   kind, or h:t+1 and h:N with N >= 1), false if none can or if Id's
%   variable is persistent or first_applicable.  RivalsOf is
%   rivals_table/3's.
rivals(Id, RivalsOf, R) :-
    get_assoc(Id, RivalsOf, R).

%   rivals_table(+Items, +Info, -RivalsOf): the assoc from the Id of each
%   random variable clause of Items to rivals/3's R.  The clauses are
%   visited from the last to the first: each one asks whether a head
%   entered so far unifies with its own, then enters its head, so that
%   only later clauses are asked.  The heads are facts of a temporary
%   module, one predicate per kind of time and name (rival_entry/3), and
%   asking is calling them: SWI-Prolog's clause indexing (on any argument,
%   also inside compound ones) answers without looking at every later
%   clause, which keeps loading near-linear in the number of clauses.
rivals_table(Items, Info, RivalsOf) :-
    info_first_applicable(Info, First),
    findall(r(Id, X, K), member(rv(Id, X, K, _, _, _), Items), Rvs0),
    sort(1, @>=, Rvs0, Rvs),
    in_temporary_module(Later, true, foldl(ddc_compile:rival(First, Later), Rvs, [], Pairs)),
    list_to_assoc(Pairs, RivalsOf).

rival(First, Later, r(Id, X, K), Pairs, [Id-R|Pairs]) :-
    functor(X, N, A),
    (   ( K == persist ; memberchk(all, First) ; memberchk(N/A, First) )
    ->  R = false
    ;   rival_questions(K, Qs),
        member(QTable-QExtra, Qs),
        rival_fact(Later, QTable, QExtra, X, G),
        current_predicate(_, G),
        \+ \+ call(G)
    ->  R = true
    ;   R = false
    ),
    (   K == persist
    ->  true
    ;   rival_entry(K, Table, Extra),
        rival_fact(Later, Table, Extra, X, F),
        assertz(F)
    ).

%   rival_entry(+Kind, -Table, -Extra): the table a head of Kind is entered
%   in, with Extra before the head's arguments.
rival_entry(u, u, []).
rival_entry(state, state, []).
rival_entry(trans, trans, []).
rival_entry(fixed(N), Table, [N]) :-
    (   N >= 1 -> Table = later ; Table = early ).

%   rival_questions(+Kind, -Tables): the tables holding the heads that a
%   clause of Kind overlaps with (h:t+1 overlaps h:N for N >= 1).
rival_questions(u, [u-[]]).
rival_questions(state, [state-[]]).
rival_questions(trans, [trans-[], later-[_]]).
rival_questions(fixed(N), Qs) :-
    (   N >= 1 -> Qs = [trans-[], later-[N]] ; Qs = [early-[N]] ).

rival_fact(Later, Table, Extra, X, Later:F) :-
    X =.. [N|Args],
    atomic_list_concat(['$rival', Table, N], '|', Name),
    append(Extra, Args, FArgs),
    F =.. [Name|FArgs].

%   Distribution code: evaluate arithmetic in the parameters; check at
%   load time when the parameters are ground, at run time otherwise.
dist_code(D, Id, File, L, Out, Code) :-
    (   var(D)
    ->  Out = '$chk'(D, Id), Code = true
    ;   ground(D)
    ->  catch(eval_dist(D, D1), E, dist_eval_error(E, D, File, L)),
        catch(dist_check(D1), error(ddc_distribution(DE, Why), _),
              throw(error(ddc(distribution(DE, Why), File:L), _))),
        Out = D1, Code = true
    ;   needs_eval(D)
    ->  Code = ddc_world:eval_dist(D, D1), Out = '$chk'(D1, Id)
    ;   Out = '$chk'(D, Id), Code = true
    ).

dist_eval_error(E, D, File, L) :-
    message_to_codes_safe(E, Why),
    throw(error(ddc(distribution(D, Why), File:L), _)).

message_to_codes_safe(E, S) :-
    catch(message_to_codes(E, S0), _, fail), !, S = S0.
message_to_codes_safe(E, E).

message_to_codes(E, S) :-
    '$messages':translate_message(E, Lines, []),
    with_output_to(string(S), print_message_lines(current_output, '', Lines)).


%   Derived atoms.
compile_der(Id, X, K, B, Info, Clause) :-
    info_impure(Info, Impure),
    X =.. [N|Args],
    Ctx = ctx(W, Now, Info, clause),
    compile_body(B, Ctx, BodyCode0),
    %   a derived atom is a ground fact of the world: a head left with
    %   variables by its body (`covers(O, A) := category(O, hand), A \== O`)
    %   is the clause's error, not an atom dropped or stored unbound
    (   ground(X)
    ->  BodyCode = BodyCode0
    ;   BodyCode = ( BodyCode0,
                     ( ground(X) -> true ; ddc_world:'$clause_error'(W, Id, non_ground_head(X)) ) )
    ),
    length(Args, Ar),
    (   K == u
    ->  (   memberchk(u/N/Ar, Impure) -> Kind = d0
        ;   memberchk(clean(u/N/Ar), Impure) -> Kind = ds
        ;   Kind = d
        ),
        derived_name(N, Kind, DN),
        append(Args, [W], HArgs),
        Head =.. [DN|HArgs],
        (   occurs_in(Now, BodyCode)
        ->  world_time_goal(W, Now, TimeGoal),
            Clause = (Head :- TimeGoal, BodyCode)
        ;   Clause = (Head :- BodyCode)
        )
    ;   tier(K, Tier),
        ( Tier == 2 -> Kind = dt2 ; Kind = dt1 ),
        derived_name(N, Kind, DN),
        time_guard(K, TArg, W, Now, Guard),
        append(Args, [TArg, W], HArgs),
        Head =.. [DN|HArgs],
        Clause = (Head :- Guard, BodyCode)
    ).

%   One dispatcher per derived predicate: world facts first, then the
%   program's clauses (memoised when impure); timed ones read materialised
%   facts at frozen times.
derived_dispatchers(M, Info, Cs) :-
    info_derived_untimed(Info, DerU), info_derived_timed(Info, DerT), info_impure(Info, Impure),
    findall(C, ( member(N/A, DerU), der_dispatch_u(M, N, A, Impure, C) ), Cu),
    findall(C, ( member(N/A, DerT), der_dispatch_t(M, N, A, Impure, C) ), Ct),
    append(Cu, Ct, Cs).

der_dispatch_u(M, N, A, Impure, C) :-
    length(Args, A),
    G =.. [N|Args],
    derived_name(N, d, DN),
    append(Args, [W], HArgs),
    Head =.. [DN|HArgs],
    (   memberchk(clean(u/N/A), Impure)
    ->  derived_name(N, ds, DNS),
        HS =.. [DNS|HArgs],
        (   (   memberchk(unit(u/N/A), Impure)
            ->  C = (Head :- HS)
            ;   C = (Head :- ddc_world:'$shared'(G, G, M:HS))
            )
        ;   C = (HS :- ddc_world:'$fact'(W, G))
        )
    ;   C = (Head :- ddc_world:'$fact'(W, G))
    ;   memberchk(u/N/A, Impure),
        derived_name(N, d0, DN0),
        Call =.. [DN0|HArgs],
        C = (Head :- ( ground(G) -> ddc_world:'$memo'(W, G, Call) ; Call ))
    ).

der_dispatch_t(M, N, A, Impure, C) :-
    length(Args, A),
    G =.. [N|Args],
    append(Args, [T, W], HArgs),
    derived_name(N, dt, DN), Head =.. [DN|HArgs],
    derived_name(N, dt0, DN0), H0 =.. [DN0|HArgs],
    derived_name(N, dt1, DN1), H1 =.. [DN1|HArgs],
    derived_name(N, dt2, DN2), H2 =.. [DN2|HArgs],
    (   memberchk(t/N/A, Impure)
    ->  (   %   (at a frozen time the materialised atoms are read directly: a
            %   memo of that read would only add its own bookkeeping)
            C = (Head :- (   ddc_world:'$frozen_at'(W, T)
                         ->  ( ground(G) -> once(H0) ; H0 )
                         ;   ground(G)
                         ->  ddc_world:'$memo'(W, G:T, H0)
                         ;   H0
                         ))
        ;   C = (H0 :- ( ddc_world:'$frozen_at'(W, T) -> ddc_world:'$mat'(W, G, T) ; H1 ))
        ;   C = (H0 :- H2)
        ;   C = (H0 :- ddc_world:'$fact'(W, G:T))
        )
    ;   memberchk(clean(t/N/A), Impure)
    ->  derived_name(N, dts, DNS), HS =.. [DNS|HArgs],
        (   C = (Head :- ddc_world:'$shared'(G:T, G:T, M:HS))
        ;   C = (HS :- ( ddc_world:'$frozen_at'(W, T) -> ddc_world:'$mat'(W, G, T) ; H1 ))
        ;   C = (HS :- H2)
        ;   C = (HS :- ddc_world:'$fact'(W, G:T))
        )
    ;   (   C = (Head :- ( ddc_world:'$frozen_at'(W, T) -> ddc_world:'$mat'(W, G, T) ; H1 ))
        ;   C = (Head :- H2)
        ;   C = (Head :- ddc_world:'$fact'(W, G:T))
        )
    ).
