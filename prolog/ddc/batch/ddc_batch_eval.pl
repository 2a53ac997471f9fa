/*  ddc_batch_eval.pl -- clause bodies and random variables over a batch.

    Part of the batched particle filter (ddc_batch.pl, the API): a clause
    body evaluated once for a batch of particles (eval_body/4), the values
    of random variables at a time drawn lazily by their first applicable
    clause (value/5), derived atoms, and the sweep of a step's transition
    clauses (sweep/5).
*/

:- module(ddc_batch_eval,
          [ eval_body/4,                % +Body, +Env, +Ps0, -Ps
            branch_union/4,             % +Goal, +Env, +Ps0, -Union
            collect/6,                  % +Template, +Goal, ?List, +Env, +Ps0, -Ps
            forget_collected/0,
            env_time_table/3,           % +Env, +T, -Table
            fact_index/2,               % +Facts, -Index
            env_at_time/3,              % +Env0, +Now, -Env
            read_time/3,                % +TimeExpr, +Env, -T
            value/5,                    % +Env, +X, +T, +Ps, -Entry
            rv_clause/6,                % +Module, ?X, ?Kind, -Dist, -Body, -Origin
            run_clause/9,               % +Env, +X, +T, +Kind, +Body, +Origin, +Ps, +C, :Action
            sweep/5                     % +Module, +Kind, +Env, +T, +All
          ]).

:- use_module(library(apply)).
:- use_module(library(lists)).
:- use_module(library(pairs)).
:- use_module(library(assoc)).
:- use_module(library(ordsets)).
:- use_module(library(error)).
:- use_module('../lang/ddc_records').
:- use_module('../lang/ddc_models', []).
:- use_module('../lang/ddc_errors', [engine_error/1]).
:- use_module(ddc_batch_program, [timed_read/3, origin_line/2, origin_id/2, origin_rivals/2]).
:- use_module(ddc_batch_tables).
:- use_module(ddc_batch_col).
:- use_module(ddc_batch_columns).
:- use_module(ddc_batch_rv, [assign/3, set_each/3]).
:- use_module('../lang/ddc_ops').

:- set_prolog_flag(optimise, true).

/** <module> Clause bodies and random variables over a batch

A body is evaluated for a batch of particles, a sorted list of particle
indices, with its variables bound to values the batch agrees on or to
column references and deferred expressions (ddc_batch_columns.pl): goals
whose inputs agree run once; comparisons, arithmetic, draws and densities
run in one loop over the batch; a goal that needs a particle's value as a
term partitions the batch by that value.  The evaluation is nondeterministic
over branches: each solution of a goal the batch agrees on, each group
of a partition, gives a branch with its own particles.

A random variable's value at a time is drawn when a body first reads it,
for the particles that lack it, by its clauses in order (h:0 or h:t+1,
then h:t), each over the particles no earlier clause gave a value
(value/5); clauses with rivals (ddc_batch_program.pl) are checked for
overlaps in the env's checked particles.

The environment of an evaluation is an env/7 record:

    env(Module, Size, Now, Tables, Facts, Observations, Checked)

Module the program's module, Size the number of particles, Now the time
that t means in the body being evaluated, Tables the tables of the two
times held (a tables/4 record, ddc_batch_tables.pl: values of the older
time are only read, a value it lacks is undefined, as in the per-particle
filter's frozen time), Facts the facts of the latest time (fact_index/2), Observations
its observations H-V, Checked the particles checked for overlapping
clauses ([] in queries and in all groups but the first).
*/

%   env(Module, Size, Now, Tables, Facts, Observations, Checked): above.
:- record_type env(module, size, now, tables, facts, observations, checked).

%   cell(Value): a value updated in place (nb_set_cell_value/2) across
%   backtracking: a counter of solutions, a flag.
:- record_type cell(value).

:- thread_local '$instance_groups'/3.           % +Ps, +Column, -Groups (instance_group/4)

:- meta_predicate run_clause(+, +, +, +, +, +, +, +, 1).

                 /*******************************
                 *         ENVIRONMENT          *
                 *******************************/

%!  env_time_table(+Env, +T, -Table) is semidet.
%
%   Table holds the columns of time T (the latest time's table or, if it
%   has one, the older time's: a pending one resampled now and kept for
%   the next query).  Fails for another time.
env_time_table(E, T, Tab) :-
    env_tables(E, Tables),
    tables_older_time(Tables, T0), tables_older(Tables, Tab0),
    tables_latest_time(Tables, T1), tables_latest(Tables, Tab1),
    (   T == T1 -> Tab = Tab1
    ;   T == T0, Tab0 \== none
    ->  (   Tab0 = pending(_, _)
        ->  real_table(Tab0, Tab),
            nb_link_tables_older(Tables, Tab)
        ;   Tab = Tab0
        )
    ).

%!  env_at_time(+Env0, +Now, -Env) is det.
%
%   Env is Env0 for a body in which t means Now.
env_at_time(E0, Now, E) :-
    env_module(E0, M), env_size(E0, N), env_tables(E0, Tables),
    env_facts(E0, Facts), env_observations(E0, Obs), env_checked(E0, Checked),
    make_env([module(M), size(N), now(Now), tables(Tables), facts(Facts), observations(Obs),
              checked(Checked)], E).

%!  read_time(+TimeExpr, +Env, -T) is semidet.
%
%   T is the time that TimeExpr (t, t+1, t-1 or 0) means in Env.
read_time(t, E, Now) :- !, env_now(E, Now).
read_time(T0+1, E, T) :- T0 == t, !, env_now(E, Now), T is Now+1.
read_time(T0-1, E, T) :- T0 == t, !, env_now(E, Now), T is Now-1.
read_time(0, _, 0).

                 /*******************************
                 *            BODIES            *
                 *******************************/
%!  eval_body(+Body, +Env, +Ps0:list(integer), -Ps:list(integer)) is nondet.
%
%   Body for the particles Ps0 (a sorted list of indices, not empty):
%   nondeterministic over branches (solutions
%   of goals the batch agrees on, partitions by value), Ps the particles of the
%   branch, each in at most one branch per solution of their own.
eval_body(_, _, [], _) :- !, fail.
eval_body(G, _, _, _) :- var(G), !,
    throw(error(instantiation_error, _)).
eval_body(true, _, Ps, Ps) :- !.
eval_body((A, B), E, Ps0, Ps) :- !,
    eval_body(A, E, Ps0, Ps1),
    eval_body(B, E, Ps1, Ps).
eval_body((C -> T ; F), E, Ps0, Ps) :- !,
    if_then_else(C, T, F, E, Ps0, Ps).
eval_body((C -> T), E, Ps0, Ps) :- !,
    if_then_else(C, T, fail, E, Ps0, Ps).
eval_body((A ; B), E, Ps0, Ps) :- !,
    (   eval_body(A, E, Ps0, Ps) ; eval_body(B, E, Ps0, Ps) ).
eval_body(\+ G, E, Ps0, Ps) :- !,
    branch_union(G, E, Ps0, Done),
    ps_subtract(Ps0, Done, Ps),
    Ps \== [].
eval_body(findall_forward(T, G, L), E, Ps0, Ps) :- !,
    collect(T, G, L, E, Ps0, Ps).
eval_body(findall(T, G, L), E, Ps0, Ps) :- !,
    collect(T, G, L, E, Ps0, Ps).
eval_body(X:TE ~= P, E, Ps0, Ps) :- !,
    read_time(TE, E, T),
    partition_batch(X, Ps0, X1, Ps1),
    read_key(X1, T, E, Ps1, K, Entry, Ps2),
    unify_read(P, K, Entry, Ps2, Ps).
eval_body(R0 ~= P, E, Ps0, Ps) :-                    % the original's current(h) = h:t, ...
    timed_read(R0, X, TE), !,
    eval_body(X:TE ~= P, E, Ps0, Ps).
eval_body(X ~= P, E, Ps0, Ps) :- !,                   % an observation of the step
    partition_batch(X, Ps0, X1, Ps1),
    env_observations(E, Obs),
    member(X1-V, Obs),
    unify_value(P, V, Ps1, Ps).
eval_body(G:TE, E, Ps0, Ps) :- !,                     % a derived atom at a time
    read_time(TE, E, T),
    partition_batch(G, Ps0, G1, Ps1),
    derived(G1, T, E, Ps1, Ps).
eval_body(V is Ex, _, Ps0, Ps) :- !,
    arith_value(V, Ex, Ps0, Ps).
eval_body(linear(Is, Ws, Y), _, Ps0, Ps) :- !,
    linear_expr(Is, Ws, Ex),
    arith_value(Y, Ex, Ps0, Ps).
eval_body(logistic(Is, Ws, P), _, Ps0, Ps) :- !,        % (1+tanh(z/2))/2 = 1/(1+exp(-z)),
    linear_expr(Is, Ws, Ex),                        %  without exp's overflow
    arith_value(P, (1 + tanh(Ex/2))/2, Ps0, Ps).
eval_body(A = B, _, Ps0, Ps) :-                      % binds a variable side as it is
    ( var(A) ; var(B) ), !,
    A = B,
    Ps = Ps0.
eval_body(G, E, Ps0, Ps) :-
    (   has_column(G)
    ->  (   test_goal(G), \+ has_free_var(G)
        ->  test_loop(G, Ps0, Ps)
        ;   partition_batch(G, Ps0, G1, Ps1),
            call_static(G1, E),
            Ps = Ps1
        )
    ;   call_static(G, E),
        Ps = Ps0
    ).

%   linear_expr(+Inputs, +Weights, -Expr): w1*x1 + ... + wn*xn + b, with
%   Weights = [w1, ..., wn, b] (ddc_models.pl's linear/3).
linear_expr(Is, Ws, Ex) :-
    must_be(list, Is), must_be(list, Ws),
    length(Is, N), N1 is N+1,
    (   length(Ws, N1) -> true
    ;   domain_error(weights_one_more_than_inputs(N), Ws)
    ),
    weighted_sum(Is, Ws, Ex).

weighted_sum([], [B], B).
weighted_sum([X|Xs], [W|Ws], W*X + Ex) :- weighted_sum(Xs, Ws, Ex).

%   call_static(+G, +Env): a static predicate of the program, a fact of
%   the step, or a builtin.
call_static(G, E) :-
    env_module(E, M),
    env_facts(E, Facts),
    (   M:'$b_static_pred'(G, Kind)
    ->  (   Kind == derived -> M:'$b_static'(G, B), static_body_call(B, E) ; M:G )
    ;   model_goal(G)                                  % softmax/3, mean_list/2, ...
    ->  ddc_models:G
    ;   visible(M, G)
    ->  M:G
    ;   indexed_fact(G, Facts)
    ).

%!  fact_index(+Facts:list, -Index) is det.
%
%   The facts of a step (the facts of an environment, read by
%   call_static/2), indexed by their predicate and, where it is a
%   constant, their first argument: a body's goal category(O, C) with O
%   bound is a look-up, not a walk over every fact of the step (12
%   objects' facts are some 40, asked for thousands of times a step).
%   The facts of a key keep their order in Facts, so that a goal's
%   solutions come in the order member/2 gives them.
fact_index(Facts, '$facts'(Assoc)) :-
    foldl(fact_keys, Facts, Pairs, []),
    keysort(Pairs, Sorted),                         % (stable: the facts' order kept)
    group_pairs_by_key(Sorted, Groups),
    list_to_assoc(Groups, Assoc).

fact_keys(F, [N/A-F|Ps], Ps0) :-
    functor(F, N, A),
    (   A > 0, arg(1, F, X), atomic(X) -> Ps = [k(N/A, X)-F|Ps0] ; Ps = Ps0 ).

%   indexed_fact(?G, +Index): G is one of the facts of an index of
%   fact_index/2.
indexed_fact(G, '$facts'(Assoc)) :-
    functor(G, N, A),
    (   A > 0, arg(1, G, X), atomic(X)
    ->  get_assoc(k(N/A, X), Assoc, Fs)
    ;   get_assoc(N/A, Assoc, Fs)
    ),
    member(G, Fs).

%   model_goal(+G): G is one of library ddc_models' (without asking
%   predicate_property/2, which looks for G in the autoload index when the
%   answer is no).
model_goal(G) :-
    functor(G, N, A),
    model_export(N, A).

%   model_export(?Name, ?Arity): ddc_models' exports, as facts made when
%   this file is compiled (module_property/2 makes the list anew at each
%   call).
term_expansion(model_exports, Facts) :-
    module_property(ddc_models, exports(Es)),
    findall(model_export(N, A), member(N/A, Es), Facts).

model_exports.

%   visible(+M, +G): G's predicate is defined in M or reachable from it
%   (imported, a builtin, autoloadable).  Asked once per predicate and
%   program: predicate_property(M:G, visible) searches the autoload index
%   each time the answer is no (a fact of the step, such as category/2,
%   asked for in every particle at every step).
visible(M, G) :-
    functor(G, N, A),
    (   M:'$b_visible'(N/A, V)
    ->  V == true
    ;   (   predicate_property(M:G, visible) -> V = true ; V = false ),
        assertz(M:'$b_visible'(N/A, V)),
        V == true
    ).

%   static_body_call(+B, +E): an untimed derived atom's body, whose goals
%   may be the step's facts (can_occlude(O) := category(O, C), ...).
static_body_call(V, _) :- var(V), !, throw(error(instantiation_error, _)).
static_body_call(true, _) :- !.
static_body_call((A, B), E) :- !, static_body_call(A, E), static_body_call(B, E).
static_body_call((A ; B), E) :- !,
    (   nonvar(A), A = (C -> T)
    ->  ( static_body_call(C, E) -> static_body_call(T, E) ; static_body_call(B, E) )
    ;   ( static_body_call(A, E) ; static_body_call(B, E) )
    ).
static_body_call((C -> T), E) :- !, ( static_body_call(C, E) -> static_body_call(T, E) ).
static_body_call(\+ A, E) :- !, \+ static_body_call(A, E).
static_body_call(findall(X, A, L), E) :- !, findall(X, static_body_call(A, E), L).
static_body_call(G, E) :- call_static(G, E).

%!  branch_union(+G, +Env, +Ps0:list(integer), -Union:list(integer)) is det.
%
%   Union: the particles of Ps0 in which G has a solution.
branch_union(G, E, Ps0, Union) :-
    col_backend(foreign), !,
    env_size(E, N),                     % (each branch's particles marked in a column, not
    col_new(N, '$u', Marks),            %  copied into a findall list)
    forall(eval_body(G, E, Ps0, Ps), col_set_each(Ps, Marks, in)),
    col_defined_at(Ps0, Marks, Union).
branch_union(G, E, Ps0, Union) :-
    findall(Ps, eval_body(G, E, Ps0, Ps), Ls),
    ps_union(Ls, Union).

%   if_then_else(+C, +T, +F, +E, +Ps0, -Ps): each particle takes T with
%   C's first solution of its own, or F if C has none.
if_then_else(C, T, F, E, Ps0, Ps) :-
    findall(Ps1, eval_body(C, E, Ps0, Ps1), Ls),
    firsts(Ls, [], Firsts, Taken),
    (   make_cell([value(0)], Counter),
        eval_body(C, E, Ps0, Ps1),
        cell_value(Counter, K0), K is K0+1, nb_set_cell_value(Counter, K),
        nth1(K, Firsts, Ps2),
        ps_intersection(Ps1, Ps2, Ps3),
        Ps3 \== [],
        eval_body(T, E, Ps3, Ps)
    ;   ps_subtract(Ps0, Taken, Rest),
        Rest \== [],
        eval_body(F, E, Rest, Ps)
    ).

firsts([], Taken, [], Taken).
firsts([L|Ls], Taken0, [F|Fs], Taken) :-
    ps_subtract(L, Taken0, F),
    ps_union(Taken0, F, Taken1),
    firsts(Ls, Taken1, Fs, Taken).

%!  collect(+T, +G, ?L, +Env, +Ps0:list(integer), -Ps:list(integer)) is nondet.
%
%   findall(T, G, L) in each particle of Ps0: L a value the batch agrees
%   on, or a column of lists.
collect(T, G, L, E, Ps0, Ps) :-
    env_now(E, Now),
    (   collected(Now-T-G, Ps0, LC0)
    ->  LC = LC0
    ;   env_size(E, N),
        col_new(N, '$u', LC),
        col_set_each(Ps0, LC, []),
        forall(eval_body(G, E, Ps0, Ps1),
               (   plan(T, Tmpl, Bs),
                   (   append_grouped(Ps1, Bs, Tmpl, LC)
                   ->  true
                   ;   append_each(Ps1, Bs, Tmpl, LC)
                   )
               )),
        remember_collected(Now-T-G, Ps0, LC)
    ),
    (   ps_first(Ps0, I0), col_all_same(Ps0, LC, I0)
    ->  col_arg(I0, LC, L0),
        unify_value(L, L0, Ps0, Ps)
    ;   unify_column(L, LC, Ps0, Ps)
    ).

%!  forget_collected is det.
%
%   Forgets the lists of findalls made so far (collected/3): called at the
%   start of each step and query, whose tables or particles they were.
forget_collected :-
    nb_setval('$ddc_collected', []),
    retractall('$instance_groups'(_, _, _)).

%   collected(+Key, +Ps, -LC): a findall of the same template and goal
%   (variants, the same columns) at the same time was made, in this step
%   or query, over particles that include Ps: LC holds their lists.  Each
%   particle's list is the same if made again (its values are drawn once),
%   so it is not: on the bench's model and the theory of occlusion the
%   clauses of hidden_under/1 run the same occluder search one after the
%   other.
collected(Key, Ps, LC) :-
    nb_current('$ddc_collected', Memo),
    member(K-Pm-LC0, Memo), K =@= Key,
    ps_subtract(Ps, Pm, []), !,
    LC = LC0.

remember_collected(Key, Ps, LC) :-
    (   nb_current('$ddc_collected', Memo) -> true ; Memo = [] ),
    nb_setval('$ddc_collected', [Key-Ps-LC|Memo]).

%   append_grouped(+Ps, +Binds, +Tmpl, !LC): append_each/4 in the column
%   library, a call per group of particles with the same values in the
%   columns the template reads (fails where the library cannot: a deferred
%   expression, a value that is not ground).
append_grouped(Ps, [], Tmpl, LC) :- !,
    col_append_each(Ps, LC, Tmpl).
append_grouped(Ps, Bs, Tmpl, LC) :-
    col_backend(foreign),
    \+ memberchk('$e'(_, _, _), Bs),
    pairs_keys_values(Bs, Cs, Pats),
    col_partition(Ps, Cs, Groups),
    forall(member(Vs-GPs, Groups),
           (   copy_term(Pats-Tmpl, Vs-T1),
               col_append_each(GPs, LC, T1)
           )).

append_each(Ps, Bs, Tmpl, LC) :-
    ps_list(Ps, Is),
    append_each_(Is, Bs, Tmpl, LC).

append_each_([], _, _, _).
append_each_([I|Is], Bs, Tmpl, LC) :-
    \+ \+ ( bind(Bs, I), col_arg(I, LC, L0), append(L0, [Tmpl], L1), col_setarg(I, LC, L1) ),
    append_each_(Is, Bs, Tmpl, LC).


%   one branch per key, the keys held at T and the ground heads that
%   clauses h:t (and h:0 at time 0) define at T, as the per-particle
%   engine enumerates them (ddc_world.pl, read_enum/4); each key is computed for
%   the particles that lack it and read where it is defined.
read_key(X, T, E, Ps0, X, Entry, Ps) :-
    ground(X), !,
    value(E, X, T, Ps0, Entry),
    Ps = Ps0.
read_key(X, T, E, Ps0, X, Entry, Ps) :-
    env_time_table(E, T, Tab),
    findall(X, table_match(Tab, X, _), Xs0),
    defined_heads(E, X, T, Ps0, Xs1),
    append(Xs0, Xs1, Xs2), sort(Xs2, Xs),
    member(X, Xs),
    value(E, X, T, Ps0, Entry),
    entry_column(Entry, C),
    defined_at(Ps0, C, Ps),
    Ps \== [].

%   defined_heads(+E, ?X, +T, +Ps, -Keys): the ground instances of X that
%   the bodies of its h:t clauses (h:0 ones at time 0) give at T, when T
%   is the time being computed (h:t+1 clauses were swept at the step);
%   found as sweep_head/6 finds them.
defined_heads(E, X, T, Ps, Keys) :-
    env_tables(E, Tables),
    tables_latest_time(Tables, T1),
    T1 == T, !,
    env_module(E, M),
    env_at_time(E, T, ES),
    (   T =:= 0 -> Kinds = [now, zero] ; Kinds = [now] ),
    findall(X1,
            ( member(K, Kinds),
              ( K == zero -> Now is T-1, env_at_time(E, Now, EK) ; EK = ES ),
              copy_term(X, X1),
              catch(sweep_head(M, K, EK, Ps, X1, _), error(ddc(non_ground_head(_), _), _), fail),
              subsumes_term(X, X1) ),
            Keys).
defined_heads(_, _, _, _, []).


%   unify_read(?P, +Key, +Entry, +Ps0, -Ps): P with the values of Entry
%   (undefined values fail).
unify_read(P, _, Entry, Ps0, Ps) :-
    entry_column(Entry, C),
    entry_status(Entry, S),
    (   S = same(V)
    ->  V \== '$undef',
        unify_value(P, V, Ps0, Ps)
    ;   S == defined
    ->  (   tuple_of_vars(P, _)
        ->  entry_tuple_arity(Entry, Arity),
            unify_column(P, C, Arity, Ps0, Ps)
        ;   unify_column(P, C, Ps0, Ps)
        )
    ;   defined_at(Ps0, C, Ps1),
        Ps1 \== [],
        unify_column(P, C, Ps1, Ps)
    ).


%!  value(+Env, +X, +T, +Ps:list(integer), -Entry) is det.
%
%   Entry: X's entry at T (a table's entry record, ddc_batch_tables.pl),
%   with a value (or '$undef') for every particle of Ps, drawn now by X's
%   first applicable clause where one lacks it (T the latest time).
value(E, X, T, Ps, Entry) :-
    env_time_table(E, T, Tab),
    (   table_get(Tab, X, Entry0)
    ->  true
    ;   env_size(E, N),
        new_column(N, '$u', C0),
        make_entry([column(C0), status(open), arity(unknown)], New),
        table_put(Tab, X, New),
        table_get(Tab, X, Entry0)
    ),
    Entry = Entry0,
    (   entry_status(Entry, open),
        env_tables(E, Tables), tables_latest_time(Tables, T)
    ->  entry_column(Entry, C),
        uncomputed(Ps, C, Miss),
        (   Miss == [] -> true ; compute(E, X, T, Miss, C) ),
        settle(Entry)
    ;   true
    ).



%   compute(+E, +X, +T, +Ps, +C): the first applicable clause's draw for
%   each particle of Ps ('$undef' where none applies).
compute(E, X, T, Ps, C) :-
    env_module(E, M),
    (   T =:= 0 -> K = zero ; K = next ),
    Now is T-1,
    env_at_time(E, Now, EK),
    env_at_time(E, T, ES),
    findall(clause_of(K, D, B, At), rv_clause(M, X, K, D, B, At), Cls1),  % (no env: a copy)
    findall(clause_of(now, D, B, At), rv_clause(M, X, now, D, B, At), Cls2),
    append(Cls1, Cls2, Cls),
    assign_clauses(Cls, EK, ES, X, T, Ps, C, Rest),
    set_each(Rest, C, '$undef').

%   assign_clauses(+Clauses, +EK, +ES, +X, +T, +Ps, +C, -Rest): each
%   clause over the particles no earlier one gave a value (Rest: those none
%   did); EK the env of the h:0/h:t+1 clauses' bodies, ES of the h:t ones.
assign_clauses([], _, _, _, _, Ps, _, Ps).
assign_clauses([clause_of(K, D, B, At)|Cls], EK, ES, X, T, Ps, C, Rest) :-
    (   Ps == []
    ->  Rest = []
    ;   ( K == now -> E = ES ; E = EK ),
        make_cell([value(false)], Any),
        assign_clause(E, X, T, K, B, D, At, Ps, C, Any),
        (   cell_value(Any, true) -> uncomputed(Ps, C, Ps1) ; Ps1 = Ps ),   % (nothing given)
        assign_clauses(Cls, EK, ES, X, T, Ps1, C, Rest)
    ).

%!  rv_clause(+M, ?X, ?Kind, -Dist, -Body, -Origin) is nondet.
%
%   A clause of X (a called clause is a fresh copy; calling with X lets
%   the clause index find X's clauses without looking at every random
%   variable's).
rv_clause(M, X, K, D, B, At) :-
    M:'$b_rv'(X, K, D, B, At).

%   A distribution error names the clause (file:line), as the per-particle
%   engine's does (ddc_world.pl, '$clause_error'/3).  The
%   particles of the env's checked list that this clause gave a value are
%   checked for a later clause that also applies (check_rivals/7).
assign_clause(E, X, T, K, B, D, At, Rest, C, Any) :-
    run_clause(E, X, T, K, B, At, Rest, C, assign_branch(Any, C, D)).

assign_branch(Any, C, D, Ps) :-
    nb_set_cell_value(Any, true),
    assign(Ps, C, D).

%!  run_clause(+Env, +X, +T, +Kind, +Body, +Origin, +Rest:list(integer), +C, :Action) is det.
%
%   call(Action, Ps) on the particles Ps of each branch of Body over
%   Rest; a distribution error names the clause's line; then the particles
%   of the env's checked list that got a value in C are checked for a
%   later clause that applies too.
run_clause(E, X, T, K, B, At, Rest, C, Action) :-
    origin_line(At, L), origin_id(At, Id), origin_rivals(At, R),
    env_module(E, M),
    env_checked(E, Check),
    catch(forall(eval_body(B, E, Rest, Ps), call(Action, Ps)), Err, clause_error(Err, M:L)),
    (   R == true, Check \== []
    ->  ps_intersection(Rest, Check, Watched),
        uncomputed(Watched, C, Missing),
        ps_subtract(Watched, Missing, Given),
        check_rivals(Given, E, X, T, K, Id, L)
    ;   true
    ).

%   clause_error(+Error, +Where): an error raised in the body of the clause
%   at Where is the program's error there, as the per-particle engine
%   reports it (ddc_errors.pl, program_error/4): a distribution error, any other
%   Prolog error or a term the program threw; the engine's own errors (which
%   name their clause) pass unchanged.
clause_error(error(ddc(Cause, W), _), Where) :-
    var(W), !,
    throw(error(ddc(Cause, Where), _)).
clause_error(error(ddc_distribution(D, Why), _), Where) :- !,
    throw(error(ddc(distribution(D, Why), Where), _)).
clause_error(E, _) :-
    engine_error(E), !,
    throw(E).
clause_error(E, Where) :-
    throw(error(ddc(prolog_error(E), Where), _)).

%   check_rivals(+Ps, +E, +X, +T, +K, +Id, +L): no clause of kind K after
%   clause Id applies to X in the particles Ps (those an earlier one gave
%   X's value); else error overlapping_clauses, at this clause's line.
check_rivals([], _, _, _, _, _, _) :- !.
check_rivals(Ps, E, X, T, K, Id, L) :-
    env_module(E, M),
    (   M:'$b_rv'(X, K, _, B, At2), origin_id(At2, Id2), Id2 > Id,
        \+ M:'$b_exclusive'(Id, Id2),
        origin_line(At2, L2),
        \+ \+ eval_body(B, E, Ps, _)
    ->  throw(error(ddc(overlapping_clauses(X:T, M:L2), M:L), _))
    ;   true
    ).

                 /*******************************
                 *        DERIVED ATOMS         *
                 *******************************/

%   derived(+G, +T, +E, +Ps0, -Ps): G at time T: from the instances
%   materialised at T (a predicate a transition body reads at t: each
%   group of particles with the same instances a branch per instance),
%   else by its clauses (each solution a branch).
derived(G, T, E, Ps0, Ps) :-
    env_module(E, M),
    functor(G, N, A),
    M:'$b_lookback'(N/A),
    env_time_table(E, T, Tab),
    table_get(Tab, '$inst'(N/A), Entry),
    !,
    entry_column(Entry, C),
    entry_status(Entry, S),
    (   S = same(L)
    ->  Ps = Ps0
    ;   instance_group(C, Ps0, L, Ps)
    ),
    member(G, L).
derived(G, T, E, Ps0, Ps) :-
    env_module(E, M),
    (   T =:= 0 -> K = zero, Now = 0 ; K = next, Now is T-1 ),
    (   M:'$b_der'(G, K, B, L), Now1 = Now         % (a called clause is a fresh copy, and
    ;   M:'$b_der'(G, now, B, L), Now1 = T         %  G its first argument: indexed)
    ),
    env_at_time(E, Now1, E1),
    catch(eval_body(B, E1, Ps0, Ps), Err, clause_error(Err, M:L)),
    (   has_free_var(G)                 % not range-restricted: as ddc_compile.pl's, an error
    ->  throw(error(ddc(non_ground_head(G), M:L), _))
    ;   true
    ).

%   instance_group(+C, +Ps0, -L, -Ps) is nondet: partition_column/4 of the
%   column C of a lookback predicate's instances: for each list of
%   instances L that particles of Ps0 hold, Ps those particles (in the
%   standard order of the lists).  A settled column of instances is not
%   changed, and a body reads it once per grounding, over the same few
%   sets of particles (occluded_by(A, O):t for each pair of objects: on a
%   table of 12 objects and a learned theory, 268 reads a step of 29
%   column and particle sets), so with the column library a partition is
%   made once per step or query (forget_collected/0) and thread.
instance_group(C, Ps0, L, Ps) :-
    col_backend(foreign), !,
    (   '$instance_groups'(Ps0, C1, Groups0), C1 == C      % (indexed on the set: a blob)
    ->  Groups = Groups0
    ;   groups_by_values(Ps0, [C], Groups),
        assertz('$instance_groups'(Ps0, C, Groups))
    ),
    member([L]-Ps, Groups).
instance_group(C, Ps0, L, Ps) :-
    partition_column(C, Ps0, L, Ps).

                 /*******************************
                 *            SWEEP             *
                 *******************************/

%!  sweep(+M, +Kind, +Env, +T, +All:list(integer)) is det.
%
%   Every ground head of a Kind clause drawn at T for the particles that
%   have it.  The heads come from the goals the clause's body starts
%   with: static goals, derived atoms (pos(A):t+1 := hidden(A):t+1, ...:
%   the per-particle filter's sweep proves the whole body), and reads at
%   t, whose keys are those held (so a value held at t that a persistence
%   clause such as h:t+1 ~ val(V) := h:t ~= V carries on is carried on in
%   the particles that hold it).
sweep(M, K, E, T, All) :-
    findall(X-Ps, sweep_head(M, K, E, All, X, Ps), Pairs0),
    keysort(Pairs0, Pairs),
    group_pairs_by_key(Pairs, Groups),
    forall(member(X-Pss, Groups),
           (   memberchk(all, Pss) -> value(E, X, T, All, _)
           ;   ps_union(Pss, Ps), value(E, X, T, Ps, _)
           )).

%   (Ps is all when the prefix is static: every particle.  A head whose
%   key reads a column, x(K):t+1 := k:t ~= K, ..., gives a key per group
%   of particles with the same value.)
%   A head the whole body leaves non-ground is an error, as in the
%   per-particle engine (ddc_world.pl's sweep_clause/5; a prefix that is
%   not the whole body may leave it to the rest).
sweep_head(M, K, E, All, X, Ps) :-
    M:'$b_rv'(H, K, _, B, At), H \= observation(_),
    origin_line(At, L),
    copy_term(H-B, X0-B1),
    sweep_prefix(B1, M, P),
    (   static_conj(P, M)
    ->  prefix_solutions(P, E), Ps = all, X = X0
    ;   eval_body(P, E, All, Ps0),
        partition_batch(X0, Ps0, X, Ps)
    ),
    (   ground(X)
    ->  true
    ;   P == B1
    ->  throw(error(ddc(non_ground_head(X), M:L), _))
    ;   fail
    ).

static_conj(true, _) :- !.
static_conj((A, B), M) :- !, static_goal(A, M), static_conj(B, M).
static_conj(A, M) :- static_goal(A, M).

prefix_solutions(true, _) :- !.
prefix_solutions((A, B), E) :- !, call_static(A, E), prefix_solutions(B, E).
prefix_solutions(A, E) :- call_static(A, E).

sweep_prefix((A, B), M, P) :- !,
    (   sweep_goal(A, M) -> P = (A, P1), sweep_prefix(B, M, P1) ; P = true ).
sweep_prefix(A, M, P) :-
    (   sweep_goal(A, M) -> P = A ; P = true ).

sweep_goal(G, M) :-
    (   nonvar(G), G = (_:TE ~= _) -> TE == t
    ;   nonvar(G), G = (D:_), callable(D) -> true        % a derived atom (hidden(A):t+1)
    ;   static_goal(G, M)
    ).

static_goal(G, M) :-
    callable(G), G \= _:_, G \= (_ ~= _), G \= (_, _), G \= (_ ; _), G \= (_ -> _),
    G \= (\+ _), G \= findall(_, _, _), G \= findall_forward(_, _, _),
    G \= (_ is _), \+ test_goal(G),
    (   M:'$b_static_pred'(G, _) -> true
    ;   model_goal(G) -> true
    ;   \+ visible(M, G)                              % a fact of the step
    ).
