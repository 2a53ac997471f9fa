/*  ddc_batch.pl -- the batched particle filter of the DDC system.

    The engine's other filter (ddc_particles.pl) proves each particle's
    clauses one particle at a time.  This one evaluates each clause once
    for a *batch* of particles (docs/batched-filter.md): the particles'
    values of a random variable at a time are one column term
    c(V1, ..., VN); a clause body runs for a list of particle indices with
    its variables bound either to one value for the whole batch or to a
    column reference; goals whose inputs agree across the batch run once,
    arithmetic, comparisons, draws and densities run in one loop over the
    batch, and a goal that needs a particle's value as a term (a key
    argument such as pos(H), a static call) partitions the batch by that value.

    ddc_filter.pl's filter_new/5 (option engine(batched)) loads the
    program and hands its items here through the engine interface's
    batched adapter (ddc_filter_batched.pl).  The module knows nothing of
    the engine's stores.

    This module is the API (filter states, steps, resampling, queries) and
    the groups of particles stepped in worker threads (the split, the
    seeds and the threads are ddc_pool.pl's, shared with the per-particle
    engine); the work is done by:

      ddc_batch_program.pl  the fragment check and the compiled program
      ddc_batch_tables.pl   the tables of columns of a time, resampling
      ddc_batch_columns.pl  goals over columns: loops, partitions, unification
      ddc_batch_rv.pl       draws and densities over a batch
      ddc_batch_eval.pl     clause bodies, random variables' values, the sweep
      ddc_batch_state.pl    a group's state record, kept across queries

    Semantics (as ddc_particles.pl's, see its header): a random variable's
    value in a particle is drawn lazily, at most once, from the first
    applicable clause (h:0 or h:t+1, then h:t as a fallback); a step
    weighs each observation by its first applicable clause's density
    (none: an error), sweeps the transition clauses' ground heads, keeps
    time t for queries and drops t-1; overlapping clauses are an error,
    looked for in the first overlap_checked_particles/1 (20) particles.
    The random draws come in another order (clause by clause over the
    particles), so the same seed gives other particles than the
    per-particle engine (docs/batched-filter.md, "What differs").

    Fragment (batch_check_program/2 names the first clause outside it,
    file:line): random variables h:0, h:t+1 and h:t; derived atoms h:t+1
    and h:t read at t+1 or in queries (not read at t in a transition body:
    those the per-particle engine materialises); static predicates (facts,
    plain Prolog clauses, untimed derived atoms with static bodies), the
    step's facts (actions, plain observations); bodies of conjunctions,
    \+, if-then-else, disjunction, reads h:t ~= P, h:t+1 ~= P, h:0 ~= P
    (current(h), next(h), prior(h) alike),
    untimed reads of an observation of the step, is/2, comparisons (a
    random variable h:t as an operand reads it), ==, \==, =, findall/3 and
    findall_forward/3, logistic/3 and linear/3, calls of static predicates
    and of Prolog's builtins; distribution parameters may be arithmetic
    expressions.
*/

:- module(ddc_batch,
          [ batch_check_program/2,      % +Items, +File
            batch_new/6,                % +Module, +Items, +N, +Seed, +Threads, -State
            batch_step/4,               % +State0, +Observations, +Facts, -Result
            batch_resample/3,           % +State0, +Indices, -State
            batch_holds/3,              % +State, +Goal, -Flags
            batch_values/4,             % +State, +Template, +Goal, -Values
            batch_rows/5,               % +State, +Template, +Goal, -Width, -Floats
            batch_packed_rows/5,        % +State, +Template, +Goal, -Width, -Rows
            batch_packed_indices/5,     % +State, ?Template, +Goal, +Atoms, -Indices
            batch_time/2,               % +State, -T
            batch_size/2,               % +State, -N
            batch_keep/2,               % +State, -Kept
            batch_module/2,             % +State, -Module
            overlap_checked_particles/1 % -N (ddc_pool.pl's)
          ]).

:- use_module(library(apply)).
:- use_module(library(lists)).
:- use_module(library(pairs)).
:- use_module('../lang/ddc_records').
:- use_module(ddc_batch_program).
:- use_module(ddc_batch_tables).
:- use_module(ddc_batch_col).
:- use_module(ddc_batch_columns, [plan/3, bind/2, partition_batch/4]).
:- use_module(ddc_batch_rv, [weigh_branch/5]).
:- use_module(ddc_batch_eval).
:- use_module(ddc_batch_state).
:- use_module('../runtime/ddc_pool', [group_seeds/2, group_sizes/3, pool_run/3, with_random_stream/3,
                          overlap_checked_particles/1]).
:- use_module('../lang/ddc_ops').

:- set_prolog_flag(optimise, true).

/** <module> Batched particle filter for DDC programs

A filter state is a group's state, a batch_state/6 record
(ddc_batch_state.pl: the program's module, the number of particles, the
time T, the column tables of times T-1 and T, the facts of time T, the
state of the group's random generator), or groups(States), a filter
whose particles are split into groups stepped in threads of their own
(see "Groups" below).  A state is never changed by a step or a
resampling (they return a new one), so the caller keeps the previous
state for undo and for errors.
*/

                 /*******************************
                 *            FILTER            *
                 *******************************/

%!  batch_new(+Module, +Items, +N, +Seed, +Threads, -State) is det.
%
%   N particles at time 0 of the program Items (ddc_read.pl's classified
%   clauses, already loaded into Module, in the fragment: see
%   batch_check_program/2): every h:0 clause's ground heads drawn.
%   Threads > 1: the particles are split into that many contiguous groups
%   (sizes differing by at most one), each with a random stream of its own
%   (the first seeded with Seed, the others with seeds drawn from it), whose
%   steps run at the same time in as many threads (see "Groups" below).
%   The particles depend on Seed and Threads, not on the machine.
batch_new(M, Items, N, Seed, K0, State) :-
    compile_batch_program(M, Items),
    K is min(K0, N),                    % (no empty group)
    (   K =:= 1
    ->  new_group(M, N, Seed, true, State)
    ;   K1 is K-1,
        with_random_stream(seed(Seed), group_seeds(K, Seeds), _),
        group_sizes(N, K, Sizes),
        length(NoChecks, K1), maplist(=(false), NoChecks),
        maplist(new_group(M), Sizes, [Seed|Seeds], [true|NoChecks], Gs),
        State = groups(Gs)
    ).

%   new_group(+M, +N, +Seed, +Check, -State): a group of N particles at
%   time 0, drawn from a stream seeded with Seed; Check: whether its first
%   particles are checked for overlapping clauses (the first group's).
new_group(M, N, Seed, Check, State) :-
    check_list(Check, N, Checked),
    table_new(Tab0), table_new(Tab),
    make_tables([older_time(-1), older(Tab0), latest_time(0), latest(Tab)], Tables),
    fact_index([], NoFacts),
    make_env([module(M), size(N), now(-1), tables(Tables), facts(NoFacts),
              observations([]), checked(Checked)], E),
    ps_all(N, All),
    forget_collected,
    with_random_stream(seed(Seed),
                       ( sweep(M, zero, E, 0, All),
                         materialise_derived(M, E, 0, All) ),
                       R),
    make_batch_state([module(M), size(N), time(0), tables(Tables), facts([]), random(R)], State).

%   materialise_derived(+M, +E, +T, +All): each lookback predicate's
%   instances at T, per particle (a list without repeats, in the order
%   its clauses give them), as the entry '$inst'(N/A) of T's table.
materialise_derived(M, E, T, All) :-
    forall(M:'$b_lookback'(N/A),
           (   functor(G, N, A),
               Now is T-1,
               env_at_time(E, Now, E1),
               env_time_table(E, T, Tab),
               env_size(E, Size),
               collect(G, G:(t+1), L, E1, All, _),
               (   L = '$c'(LC, _, _)
               ->  col_new(Size, '$u', C),
                   (   col_sets_each(All, LC, C) -> true ; sets_each(All, LC, C) )
               ;   list_to_set(L, Set), col_new(Size, Set, C)
               ),
               make_entry([column(C), status(open), arity(none)], Entry0),
               table_put(Tab, '$inst'(N/A), Entry0),
               table_get(Tab, '$inst'(N/A), Entry),
               settle(Entry)
           )).

sets_each(Ps, LC, C) :-
    ps_list(Ps, Is),
    sets_each_(Is, LC, C).

sets_each_([], _, _).
sets_each_([I|Is], LC, C) :-
    col_arg(I, LC, L), list_to_set(L, Set), col_setarg(I, C, Set),
    sets_each_(Is, LC, C).

%!  batch_step(+State0, +Observations, +Facts, -Result) is det.
%
%   Result = step(State, LogWeights): every particle advanced from t to
%   t+1 with the Facts (actions and plain observations) of t+1 and
%   weighted by the Observations (terms H ~= V).  State0 is not changed.
batch_step(groups([G1|Gs]), Obs, Facts, step(groups([S1|Ss]), LWs)) :- !,
    maplist(step_job(Obs, Facts), Gs, Jobs),
    pool_run(group_step(G1, Obs, Facts, true, step(S1, LWs1)), Jobs, Results),
    maplist(group_done(Facts), Gs, Results, Ss, LWss),
    append([LWs1|LWss], LWs),
    col_collect_garbage.
batch_step(State0, Obs, Facts, Result) :-
    group_step(State0, Obs, Facts, true, Result),
    col_collect_garbage.

%   check_list(+Check, +N, -Checked): the particles a group checks for
%   overlapping clauses (none unless Check is true).
check_list(true, N, Checked) :- !,
    overlap_checked_particles(K0), K is min(N, K0), numlist(1, K, Checked).
check_list(false, _, []).

%   group_step(+State0, +Obs, +Facts, +Check, -Result): batch_step/4 of
%   one group; Check: whether its first particles are checked for
%   overlapping clauses (the first group's).
group_step(State0, Obs, Facts, Check, step(State, LWs)) :-
    batch_state_module(State0, M), batch_state_size(State0, N), batch_state_time(State0, T),
    batch_state_tables(State0, Tables0), tables_latest(Tables0, Tab),
    batch_state_random(State0, R0),
    check_list(Check, N, Checked),
    T1 is T+1,
    table_new(Tab1),
    findall(H-V, member(H ~= V, Obs), HVs),
    make_tables([older_time(T), older(Tab), latest_time(T1), latest(Tab1)], Tables),
    fact_index(Facts, FactIndex),
    make_env([module(M), size(N), now(T), tables(Tables), facts(FactIndex),
              observations(HVs), checked(Checked)], E),
    ps_all(N, All),
    new_column(N, 0.0, LW),
    forget_collected,
    with_random_stream(state(R0),
                       ( forall(member(H-V, HVs), weigh_observation(E, H, V, All, LW)),
                         sweep(M, next, E, T1, All),
                         materialise_derived(M, E, T1, All) ),
                       R),
    col_list(LW, LWs),
    duplicate_term(Facts, Facts1),
    make_batch_state([module(M), size(N), time(T1), tables(Tables), facts(Facts1),
                      random(R)], State).

%   weigh_observation(+E, +H, +V, +Ps, +LW): the log density of V under
%   H's first applicable clause at t+1, added to each particle's LW.
weigh_observation(E, H, V, Ps, LW) :-
    env_module(E, M), env_size(E, N), env_now(E, T),
    T1 is T+1,
    new_column(N, '$u', Done),
    forall(rv_clause(M, H, next, D, B, At),
           weigh_clause(E, H, T1, next, B, D, At, V, Ps, Done, LW)),
    env_at_time(E, T1, ES),
    forall(rv_clause(M, H, now, D, B, At),
           weigh_clause(ES, H, T1, now, B, D, At, V, Ps, Done, LW)),
    (   col_uncomputed(Ps, Done, Missing), Missing \== []
    ->  throw(error(ddc(no_observation_clause(H ~= V), query), _))
    ;   true
    ).

%   (A distribution error names the clause; overlaps are checked as for
%   draws: run_clause/9.)
weigh_clause(E, H, T, K, B, D, At, V, Ps, Done, LW) :-
    uncomputed(Ps, Done, Rest),
    (   Rest == [] -> true
    ;   run_clause(E, H, T, K, B, At, Rest, Done, weigh_branch(D, V, Done, LW))
    ).

%!  batch_resample(+State0, +Indices, -State) is det.
%
%   Particle i (1-based position in Indices) becomes a copy of particle
%   Indices[i] (0-based).  The latest time's columns are resampled now,
%   the previous time's when a query first reads them (pending/2).  Each
%   group keeps its random stream.
batch_resample(S0, Is0, S) :-
    state_groups(S0, Gs0),
    maplist(batch_size, Gs0, Sizes),
    maplist(latest_table, Gs0, Src1),
    maplist(older_table, Gs0, Src0),
    sources(Is0, Sizes, Pairs),
    maplist(resampled_group(Src0, Src1), Gs0, Pairs, Gs),
    (   S0 = groups(_) -> S = groups(Gs) ; Gs = [S] ).

state_groups(groups(Gs), Gs) :- !.
state_groups(S, [S]).

%   (Tab is bound by unification, not by the accessor: an older table is
%   kept in pending/2 after the query, and a binding that arg/3 makes is
%   trailed, so undone when the query ends, even a fresh variable's.)
latest_table(S, Tab) :-
    batch_state_tables(S, Tables), tables_latest(Tables, Tab0), Tab = Tab0.
older_table(S, Tab) :-
    batch_state_tables(S, Tables), tables_older(Tables, Tab0), Tab = Tab0.

%   sources(+Indices, +Sizes, -Pairs): for each group (of Sizes), its
%   particles' ancestors as Group-Index pairs (1-based).
sources(Is, Sizes, Pairs) :-
    col_sources(Is, Sizes, Pairs), !.
sources(Is, Sizes, Pairs) :-
    maplist(source(Sizes), Is, All),
    split_by(Sizes, All, Pairs).

source(Sizes, J, G-L) :- source(Sizes, 1, J, G, L).
source([Size|Sizes], G0, J, G, L) :-
    (   J < Size -> G = G0, L is J+1
    ;   J1 is J-Size, G1 is G0+1, source(Sizes, G1, J1, G, L)
    ).

split_by([], [], []).
split_by([Size|Sizes], All, [P|Ps]) :-
    length(P, Size),
    append(P, Rest, All),
    split_by(Sizes, Rest, Ps).

%   resampled_group(+Src0, +Src1, +S0, +Pairs, -S): group S0 with the
%   particles Pairs of all groups' tables (Src1 the latest, resampled now;
%   Src0 the older, pending).
resampled_group(Src0, Src1, S0, Pairs, S) :-
    batch_state_module(S0, M), batch_state_size(S0, Size), batch_state_time(S0, T),
    batch_state_tables(S0, Tables0),
    tables_older_time(Tables0, T0), tables_latest_time(Tables0, T1),
    batch_state_facts(S0, Facts), batch_state_random(S0, R),
    resample_tables(Src1, Pairs, New1),
    make_tables([older_time(T0), older(pending(Src0, Pairs)), latest_time(T1), latest(New1)],
                Tables),
    make_batch_state([module(M), size(Size), time(T), tables(Tables), facts(Facts),
                      random(R)], S).

%!  batch_keep(+State, -Kept) is det.
%
%   Kept is State's skeleton assembled anew by non-backtrackable
%   assignment (nb_linkarg/3), sharing State's tables, facts and streams:
%   a term a filter may keep linked in a global variable across queries.
%   (A state is made by unification; a binding made while a choice point
%   was newer than the variable is undone by backtracking to it, even
%   after the term is linked, e.g. when the query that made it ends.  The
%   tables and columns are made by non-backtrackable assignment already.)
batch_keep(groups(Gs), Kept) :- !,
    maplist(batch_keep, Gs, Ks),
    kept_list(Ks, L),
    new_groups(Kept),
    nb_link_groups_states(Kept, L).
batch_keep(S, Kept) :-
    state_keep(S, Kept).

%   kept_list(+Xs, -L): the list Xs, its cells made by nb_linkarg/3 (a
%   list cell '[|]'(Head, Tail), not a record: the only numeric arg/3
%   family call here).
kept_list([], []).
kept_list([X|Xs], L) :-
    kept_list(Xs, L1),
    functor(L, '[|]', 2),
    nb_linkarg(1, L, X),
    nb_linkarg(2, L, L1).

%!  batch_module(+State, -Module) is det.
%
%   The module the state's program is loaded into.
batch_module(groups([G|_]), M) :- !, batch_module(G, M).
batch_module(S, M) :- batch_state_module(S, M).

%!  batch_time(+State, -T) is det.
%
%   The state's time: the number of steps since the filter's start.
batch_time(groups([G|_]), T) :- !, batch_time(G, T).
batch_time(S, T) :- batch_state_time(S, T).

%!  batch_size(+State, -N) is det.
%
%   The state's number of particles.
batch_size(groups(Gs), N) :- !, foldl(add_size, Gs, 0, N).
batch_size(S, N) :- batch_state_size(S, N).

add_size(G, N0, N) :- batch_size(G, K), N is N0+K.

%!  batch_holds(+State, +Goal, -Flags) is det.
%
%   Flags: for each particle 1 if Goal holds at the current time (t is the
%   current time), else 0.  Values the goal needs and a particle lacks are
%   drawn and kept (the state's columns are updated in place).
batch_holds(groups(Gs), Goal, Flags) :- !,
    maplist(group_holds(Goal), Gs, Fss),
    append(Fss, Flags).
batch_holds(S, Goal, Flags) :-
    query_env(S, E, All),
    with_state(S, branch_union(Goal, E, All, Ps)),
    batch_state_size(S, N),
    ps_list(Ps, L),
    flags(1, N, L, Flags).

%   (Each group's query on a copy of the goal: its bindings are its own.)
group_holds(Goal, G, Flags) :-
    copy_term(Goal, Goal1),
    batch_holds(G, Goal1, Flags).

flags(I, N, _, []) :- I > N, !.
flags(I, N, [I|Ps], [1|Fs]) :- !, I1 is I+1, flags(I1, N, Ps, Fs).
flags(I, N, Ps, [0|Fs]) :- I1 is I+1, flags(I1, N, Ps, Fs).

%!  batch_values(+State, +Template, +Goal, -Values) is det.
%
%   Values: for each particle Template at Goal's first solution of its own,
%   or the atom none.
batch_values(groups(Gs), Template, Goal, Values) :- !,
    maplist(group_values(Template-Goal), Gs, Vss),
    append(Vss, Values).
batch_values(S, Template, R0 ~= V, Values) :-
    timed_read(R0, X, TE), !,
    batch_values(S, Template, X:TE ~= V, Values).
batch_values(S, Template, Goal, Values) :-          % a variable's values: read as they are
    nonvar(Goal), Goal = (X:TE ~= V), var(V), ground(X),
    (   Template == V -> Wrap = plain ; Template == value(V) -> Wrap = value ),
    !,
    query_env(S, E, All),
    read_time(TE, E, T),
    (   env_time_table(E, T, _)
    ->  with_state(S, value(E, X, T, All, Entry)),
        entry_column(Entry, C),
        col_list(C, Vs),
        maplist(wrapped_value(Wrap), Vs, Values)
    ;   batch_state_size(S, N),
        length(Values, N), maplist(=(none), Values)
    ).
batch_values(S, Template, Goal, Values) :-
    query_env(S, E, All),
    batch_state_size(S, N),
    new_column(N, none, VC),
    new_column(N, '$u', Done),
    with_state(S, forall(eval_body(Goal, E, All, Ps),
                         ( plan(Template, Tmpl, Bs), ps_list(Ps, L),
                           value_each(L, Bs, Tmpl, Done, VC) ))),
    col_list(VC, Values).

%!  batch_rows(+State, +Template, +Goal, -Width, -Floats) is semidet.
%
%   batch_values/4 of a variable's values (Goal X:t ~= V, Template V) as
%   rows of Width floats, particle by particle (NaN rows where undefined),
%   read straight from the columns (the column library's col_rows/4);
%   fails for any other goal, where a value is not a number tuple of
%   floats, or where no particle has a value (the caller then makes the
%   rows from batch_values/4's values).
batch_rows(S, Template, Goal, W, Floats) :-
    row_columns(S, Template, Goal, W, Cs),
    foldl(column_rows(W), Cs, Floats, []).

column_rows(W, C, Fs0, Fs) :- col_rows(C, W, Fs0, Fs).

%!  batch_packed_rows(+State, +Template, +Goal, -Width, -Rows) is semidet.
%
%   batch_rows/5 with the floats in a blob of doubles
%   (ddc_batch_col:col_pack_rows/3).
batch_packed_rows(S, Template, Goal, W, Rows) :-
    row_columns(S, Template, Goal, W, Cs),
    col_pack_rows(Cs, W, Rows).

%!  batch_packed_indices(+State, ?Template, +Goal, +Atoms, -Indices) is semidet.
%
%   Per particle, the 0-based position in Atoms of Template at the first
%   of Goal's solutions whose Template is one of Atoms, as a blob of
%   doubles (col_pack_rows/3; NaN where there is none): each solution of
%   Goal (a set of particles) sets the particles not yet set.  Fails
%   where a solution binds Template to something other than an atom in a
%   particle, or without the column library.
batch_packed_indices(S, Template, Goal, Atoms, Indices) :-
    state_groups(S, Gs),
    maplist(group_index_column(Template-Goal, Atoms), Gs, Cs),
    col_pack_rows(Cs, 1, Indices).

group_index_column(TG, Atoms, G, C) :-
    copy_term(TG, Template-Goal),
    query_env(G, E, All),
    batch_state_size(G, N),
    col_new(N, '$u', C),
    with_state(G, forall(eval_body(Goal, E, All, Ps), set_index(Template, Atoms, Ps, C))).

%   (A solution's Template is one atom for all of its particles, or a
%   column of them, partitioned into the groups of particles that agree.)
set_index(Template, Atoms, Ps, C) :-
    forall(partition_batch(Template, Ps, Value, Ps1), set_index_value(Value, Atoms, Ps1, C)).

set_index_value(Value, Atoms, Ps, C) :-
    atom(Value),
    (   nth0(I, Atoms, Value)
    ->  X is float(I),
        col_set_each(Ps, C, X)
    ;   true
    ).

%   row_columns(+S, +Template, +Goal, -W, -Columns): the columns of each
%   group's values of the variable of Goal (every one computed), and the
%   tuple arity W of their values (fails where a value is no tuple of W
%   floats, or no particle has one).
row_columns(S, Template, Goal, W, Cs) :-
    state_groups(S, Gs),
    maplist(group_column(Template-Goal), Gs, Cs),
    foldl(column_width, Cs, _, W),
    integer(W).

column_width(C, W0, W) :-
    col_row_width(C, K),
    (   K =:= 0 -> W = W0 ; var(W0) -> W = K ; W0 == K, W = W0 ).

group_column(TG, G, C) :-
    copy_term(TG, Template-Goal0),
    nonvar(Goal0),
    (   Goal0 = (R0 ~= V0), timed_read(R0, X0, TE0) -> Goal = (X0:TE0 ~= V0) ; Goal = Goal0 ),
    Goal = (X:TE ~= V), var(V), ground(X), Template == V,
    query_env(G, E, All),
    read_time(TE, E, T),
    env_time_table(E, T, _),
    with_state(G, value(E, X, T, All, Entry)),
    entry_column(Entry, C).

wrapped_value(Wrap, V, W) :-
    (   ( V == '$undef' ; V == '$u' ) -> W = none
    ;   Wrap == value -> W = value(V)
    ;   W = V
    ).

group_values(TG, G, Values) :-
    copy_term(TG, Template-Goal),
    batch_values(G, Template, Goal, Values).

value_each([], _, _, _, _).
value_each([I|Is], Bs, Tmpl, Done, VC) :-
    (   col_is_u(I, Done)
    ->  col_setarg(I, Done, done),
        \+ \+ ( bind(Bs, I), col_setarg(I, VC, Tmpl) )
    ;   true
    ),
    value_each(Is, Bs, Tmpl, Done, VC).

                 /*******************************
                 *            GROUPS            *
                 *******************************/

%   A filter of K > 1 groups is groups([S1, ..., SK]), each Si a filter
%   state of its own particles (contiguous: S1's first, ...).  A step
%   steps S1 in the calling thread and each other group in a worker thread
%   (kept for the life of the process, shared by all filters), which gets a
%   copy of the group's latest table only (a step reads no older one) and
%   sends back the stepped group.  Resampling joins the groups into one
%   state, resamples it and splits it again (each group keeps its stream);
%   queries ask each group in turn.

%   step_job(+Obs, +Facts, +G, -Job): the job (ddc_pool.pl's pool_run/3)
%   that steps group G in a worker thread; the worker gets G with its
%   latest table only (the older one none).
step_job(Obs, Facts, G, worker_step(Sent, Obs, Facts, Out)-Out) :-
    batch_state_module(G, M), batch_state_size(G, N), batch_state_time(G, T),
    batch_state_tables(G, Tables0), tables_latest_time(Tables0, T), tables_latest(Tables0, Tab),
    batch_state_facts(G, Fs), batch_state_random(G, R),
    make_tables([older_time(none), older(none), latest_time(T), latest(Tab)], Tables),
    make_batch_state([module(M), size(N), time(T), tables(Tables), facts(Fs), random(R)], Sent).

%   A worker sends back only what is new: the table of t+1, the weights
%   and its stream; the group's table of t is the one this thread holds.
worker_step(S0, Obs, Facts, done(T1, Tab1, R, LWs)) :-
    group_step(S0, Obs, Facts, false, step(S, LWs)),
    batch_state_time(S, T1),
    batch_state_tables(S, Tables), tables_latest(Tables, Tab1),
    batch_state_random(S, R).

group_done(Facts, G, done(T1, Tab1, R, LWs), S, LWs) :-
    batch_state_module(G, M), batch_state_size(G, N), batch_state_time(G, T),
    batch_state_tables(G, Tables0), tables_latest(Tables0, Tab),
    duplicate_term(Facts, Facts1),
    make_tables([older_time(T), older(Tab), latest_time(T1), latest(Tab1)], Tables),
    make_batch_state([module(M), size(N), time(T1), tables(Tables), facts(Facts1), random(R)],
                     S).
