/*  ddc_batch_columns.pl -- goals over columns, as loops over a batch.

    Part of the batched particle filter (ddc_batch.pl, the API): the
    terms a clause body's variables are bound to when their values differ
    between particles (column references, deferred expressions), and the
    loops that run a goal over a batch of particles: tests, arithmetic,
    instances of a template (compiled to virtual-machine clauses for large
    batches), partitions of a batch by value, unification with a column.
*/

:- module(ddc_batch_columns,
          [ plan/3,                     % +Term, -Template, -Binds
            bind/2,                     % +Binds, +I
            has_column/1,               % +Term
            has_free_var/1,             % +Term
            materialise/3,              % +Term, +Ps, -Term1
            arith_value/4,              % ?V, +Expr, +Ps0, -Ps
            test_goal/1,                % +Goal
            test_loop/3,                % +Goal, +Ps0, -Ps
            compiled_instance/4,        % +Ps, +Binds, +Template, !Column
            vm_finite/4,                % +Ps, +Binds, +Entries, !Column
            partition_batch/4,                    % +Term, +Ps0, -Term1, -Ps
            partition_column/4,             % +Column, +Ps0, -V, -Ps
            groups_by_values/3,         % +Ps, +Columns, -Groups
            unify_value/4,              % ?P, +V, +Ps0, -Ps
            unify_column/4,             % ?P, +Column, +Ps0, -Ps
            unify_column/5,             % ?P, +Column, +Arity, +Ps0, -Ps
            tuple_of_vars/2             % +P, -Vars
          ]).

:- use_module(library(apply)).
:- use_module(library(lists)).
:- use_module(library(pairs)).
:- use_module(ddc_batch_tables, [tuple_shape/2]).
:- use_module(ddc_batch_col).
:- use_module('../lang/ddc_body', [conj_from_list/2]).
:- use_module('../lang/ddc_programs', [optimised/1]).

:- set_prolog_flag(optimise, true).

/** <module> Goals over columns for the batched filter

A particle index is an integer 1..N; a batch is a sorted list of them.
Columns (ddc_batch_col.pl) are read and written by particle index
(col_arg/3, col_setarg/3): they are arrays, not records.

Body variables are bound to values (the same for the whole batch) or
to column references '$c'(C, Pattern, V): the particle's value in
column C unifies with Pattern, whose variable V is the variable's value
(Pattern = V for a plain read; a tuple of fresh variables, one of
them V, for a read such as pos(O):t ~= (X, Y, Z), whose three
references share the one Pattern: one unification per particle binds
all three), or to a deferred expression '$x'(Expr): `V is Expr` over
columns is not computed into a column of its own but evaluated in the
loop of each goal that reads V (a comparison, a draw, a head's value),
so that X1 is X + DX, Y1 is ..., then val((X1, Y1, Z1)) costs one loop
over the batch, not four.  A goal that needs V's value as a term (a
partition) gets it computed into a column first (materialise/3).
*/

%!  plan(+T, -Tmpl, -Binds:list) is det.
%
%   Tmpl is T with each '$c'(C, Pattern, V)
%   replaced by V and each '$x'(Expr) by a variable W, Binds the C-Pattern
%   pairs and '$e'(W, ExprTmpl, '$x'(Expr)) evaluations (each once, an
%   evaluation after the bindings it reads): bind/2 makes Tmpl a
%   particle's instance.
plan(T, Tmpl, Binds) :-
    map_term(plan_leaf, T, Tmpl, [], Binds0),
    reverse(Binds0, Binds).

plan_leaf('$c'(C, P, V), V, Bs0, Bs) :-
    (   member(C0-P0, Bs0), C0 == C, P0 == P -> Bs = Bs0 ; Bs = [C-P|Bs0] ).
plan_leaf(X, W, Bs0, Bs) :-
    X = '$x'(Ex),
    (   member('$e'(W0, _, X0), Bs0), X0 == X
    ->  W = W0, Bs = Bs0
    ;   map_term(plan_leaf, Ex, ExT, Bs0, Bs1),
        Bs = ['$e'(W, ExT, X)|Bs1]
    ).

%   map_term(:Leaf, +T, -T1, +A0, -A): T with each subterm S for which
%   call(Leaf, S, S1, A0, A) succeeds replaced by S1 (its arguments not
%   visited), the others copied, A threaded through the leaves from left
%   to right.
:- meta_predicate map_term(4, +, -, +, -).
map_term(_, T, T, A, A) :- var(T), !.
map_term(Leaf, T, T1, A0, A) :- call(Leaf, T, T1, A0, A), !.
map_term(_, T, T, A, A) :- atomic(T), !.
map_term(Leaf, T, T1, A0, A) :-
    compound_name_arguments(T, F, As),
    map_args(As, Leaf, As1, A0, A),
    compound_name_arguments(T1, F, As1).

map_args([], _, [], A, A).
map_args([X|Xs], Leaf, [Y|Ys], A0, A) :-
    map_term(Leaf, X, Y, A0, A1),
    map_args(Xs, Leaf, Ys, A1, A).

%!  bind(+Binds:list, +I:integer) is semidet.
%
%   Makes plan/3's template particle I's instance: binds each column's
%   pattern to the particle's value, evaluates each deferred expression.
bind([], _).
bind([B|Bs], I) :- bind_one(B, I), bind(Bs, I).

bind_one(C-P, I) :- col_arg(I, C, P).
bind_one('$e'(W, Ex, _), _) :- W is Ex.

%   column_ref(+Column, ?V, -Ref): Ref is a reference to Column whose
%   particle value is V itself.
column_ref(C, V, '$c'(C, V, V)).

%!  has_column(+T) is semidet.
%
%   T holds a column reference or a deferred expression.  (A reference
%   may be ground: a partition binds its pattern to the value of the branch's
%   particles, and the reference still reads the column, so no ground(T)
%   short cut.)
has_column(T) :-
    col_has_ref(T).

%!  materialise(+T, +Ps:list(integer), -T1) is det.
%
%   T1 is T with each deferred expression computed
%   into a column, for the particles Ps.
materialise(T, Ps, T1) :-
    (   deferred_in(T, X)
    ->  X = '$x'(Ex),
        once(column_in(Ex, C0)),
        col_size(C0, N),
        plan(X, W, Bs),
        col_new(N, '$u', C),
        arith_loop(Ps, Bs, W, C),
        column_ref(C, _, Ref),
        replace_eq(T, X, Ref, T2),
        materialise(T2, Ps, T1)
    ;   T1 = T
    ).

%   deferred_in(+T, -X): a deferred expression in T (not looking inside
%   column references: a column has an argument per particle).
deferred_in(T, X) :-
    compound(T),
    (   T = '$x'(_) -> X = T
    ;   T = '$c'(_, _, _) -> fail
    ;   arg(_, T, A), deferred_in(A, X)
    ), !.

%   column_in(+Ex, -C): a column Ex reads.
column_in(T, C) :-
    compound(T),
    (   T = '$c'(C0, _, _) -> C = C0
    ;   arg(_, T, A), column_in(A, C)
    ).

replace_eq(T, X, Y, T1) :-
    map_term(replace_leaf(X, Y), T, T1, none, _).

replace_leaf(X, Y, T, T1, A, A) :-
    (   T == X -> T1 = Y
    ;   T = '$c'(_, _, _) -> T1 = T             % (a column: not walked)
    ).

%!  arith_value(?V, +Ex, +Ps0:list(integer), -Ps:list(integer)) is semidet.
%
%   V is Ex, over columns or not: a variable V becomes the deferred
%   expression; a bound V is compared with Ex in each particle of Ps0 (Ps
%   those where it holds).
arith_value(V, Ex, Ps0, Ps) :-
    (   has_column(Ex), var(V) -> V = '$x'(Ex), Ps = Ps0
    ;   ( has_column(V) ; has_column(Ex) ) -> test_loop(V =:= Ex, Ps0, Ps)
    ;   V is Ex, Ps = Ps0
    ).


%!  has_free_var(@T) is semidet.
%
%   T has a variable of its own (not one inside a column
%   reference or a deferred expression, which each particle binds).
has_free_var(T) :- var(T), !.
has_free_var(T) :-
    compound(T), T \= '$c'(_, _, _), T \= '$x'(_),
    arg(_, T, A), has_free_var(A), !.

%!  test_goal(+G) is semidet.
%
%   G is a goal that can run particle by particle as a test when it has no
%   variables to bind (all bound to values or columns): a comparison or a
%   unification.
test_goal(G) :-
    compound(G), functor(G, Op, 2),
    memberchk(Op, [<, >, =<, >=, =:=, =\=, ==, \==, =, \=, @<, @>, @=<, @>=]).

arith_loop(Ps, Bs, Ex, C) :-
    ps_list(Ps, Is),
    arith_loop_(Is, Bs, Ex, C).

arith_loop_([], _, _, _).
arith_loop_([I|Is], Bs, Ex, C) :-
    \+ \+ ( bind(Bs, I), X is Ex, col_setarg(I, C, X) ),
    arith_loop_(Is, Bs, Ex, C).

%!  test_loop(+G, +Ps0:list(integer), -Ps:list(integer)) is semidet.
%
%   Ps: the particles of Ps0 in which the test G holds (not empty).  A
%   batch of 16 or more particles runs a compiled loop (compiled_test/4).
test_loop(G, Ps0, Ps) :-
    (   col_test(Ps0, G, Ps1)                 % (in the column library, from G itself)
    ->  Ps = Ps1
    ;   plan(G, Tmpl, Bs),
        (   ps_size(Ps0, K), K >= 16
        ->  compiled_test(Ps0, Bs, Tmpl, Ps)
        ;   ps_list(Ps0, L),
            test_each(L, Bs, Tmpl, Ps)
        )
    ),
    Ps \== [].

%   compiled_test(+Ps0, +Binds, +Test, -Ps): test_each/4 as a loop compiled
%   for the goal (its arithmetic compiled to virtual-machine instructions,
%   as the per-particle engine's clauses are; a particle's values bound by
%   unification in the clause, no undo between particles), for batches
%   large enough to pay for it.  A loop is compiled once per shape of goal:
%   its numbers are arguments (they change from step to step), so the
%   number of loops is bounded by the program's goals, and none is ever
%   retracted (a retracted clause waits for the clause garbage collector,
%   which a forked process, such as anchoring evaluate's workers, does not
%   have: loops asserted and retracted per batch made each run there seven
%   times slower).
compiled_test(Ps0, Bs, Tmpl, Ps) :-
    col_backend(foreign),
    vm_test(Ps0, Bs, Tmpl, Ps), !.
compiled_test(Ps0, Bs, Tmpl, Ps) :-
    bind_goals(Bs, I, Cs, CVs, Gets, Evals),
    append([Gets, Evals, [Tmpl]], Gs),
    conj_from_list(Gs, Cond0),
    abstract_numbers(Cond0, Cond, Ks),
    pairs_keys_values(Ks, KVs, Ns),
    Head =.. [cols|CVs],
    compiled_loop(test, Head, k(KVs), I, Cond, Name),
    Cols =.. [cols|Cs],
    ps_list(Ps0, L),
    call(Name, L, Cols, k(Ns), Ps).

%   vm_test(+Ps0, +Binds, +Test, -Ps) and vm_instance(+Ps, +Binds, +Tmpl,
%   !C): compiled_test/4 and compiled_instance/4 in one call of the column
%   library (col_vm_test/7, col_vm_instance/5), for a comparison of
%   arithmetic over number tuples and a tuple of floats computed from them;
%   fail (the caller's Prolog loop runs) for any other goal, or where the
%   library abandons the loop (a value that is not a number tuple, an
%   arithmetic error).  An instance's components must be floats whatever
%   the particle (computed from a column's floats or float constants), as
%   the Prolog loop would give them.
vm_test(Ps0, [C-P], Tmpl, Ps) :-
    var(P), compound(Tmpl), Tmpl =.. [Op, A, B],
    memberchk(Op-Eq, [(==)-true, (\==)-false]),
    (   A == P, ground(B) -> V = B
    ;   B == P, ground(A) -> V = A
    ), !,
    col_select_eq(Ps0, C, V, Eq, Ps).
vm_test(Ps0, Bs, Tmpl, Ps) :-
    compound(Tmpl), Tmpl =.. [Op, A, B],
    memberchk(Op, [<, >, =<, >=, =:=, =\=]),
    vm_binds(Bs, S1),
    vm_expr(A, RA, _, S1, S2),
    vm_expr(B, RB, _, S2, S),
    vm_state(S, Cols, Code),
    col_vm_test(Ps0, Cols, Code, Op, RA, RB, Ps).

%!  vm_finite(+Ps, +Binds, +Entries, !C) is semidet.
%
%   Each particle of Ps not drawn yet in C gets a draw of finite(Entries)
%   (a plan/3 template: its probabilities variables the binds compute or
%   numbers, its values ground), in one call of the column library; fails
%   where it cannot (the caller draws in Prolog).
vm_finite(Ps, Bs, Es, C) :-
    is_list(Es), Es \== [],
    pairs_of_entries(Es, Ws, Vs),
    ground(Vs),
    vm_binds(Bs, S1),
    foldl(vm_prob, Ws, Rs, S1, S2),
    S2 = vm(_, Code0, _, _),
    (   Code0 == [] -> S = vm([], [cst(0, 0.0)], [], 1) ; S = S2 ),  % (a program is not empty)
    vm_state(S, Cols, Code),
    col_from_list(Vs, Values),
    col_size(C, N), N > 0,
    random_between(0, 0x3fffffffffffffff, Seed),
    col_vm_finite(Ps, Cols, Code, Rs, Values, C, Seed).

pairs_of_entries([], [], []).
pairs_of_entries([E|Es], [W|Ws], [V|Vs]) :-
    nonvar(E), E = W:V,
    pairs_of_entries(Es, Ws, Vs).

vm_prob(W, R, S0, S) :-
    ( var(W) ; number(W) ), !,
    vm_expr(W, R, _, S0, S).

vm_instance(Ps, [C1-P], Tmpl, C) :-
    var(P), Tmpl == P, !,
    col_copy_each(Ps, C1, C).
vm_instance(Ps, Bs, Tmpl, C) :-
    vm_binds(Bs, S1),
    (   nonvar(Tmpl), Tmpl = (_, _) -> conj_to_list(Tmpl, Es) ; Es = [Tmpl] ),
    foldl(vm_float_expr, Es, Rs, S1, S),
    vm_state(S, Cols, Code),
    col_vm_instance(Ps, Cols, Code, Rs, C).

conj_to_list(T, [A|Es]) :-
    nonvar(T), T = (A, B), !,
    conj_to_list(B, Es).
conj_to_list(T, [T]).

%   (A component is a variable or a float: a template is instantiated,
%   not evaluated; its arithmetic comes as deferred expressions, '$e'
%   bindings.)
vm_float_expr(E, R, S0, S) :-
    ( var(E) ; float(E) ), !,
    vm_expr(E, R, true, S0, S).

%   The compiler's state: vm(Columns, Code, Env, Next), Columns and Code
%   reversed, Env the variables' registers V-R-Float (Float true: a float
%   in every particle), Next the next free register.
vm_binds(Bs, S) :-
    foldl(vm_bind, Bs, vm([], [], [], 0), S).

vm_state(vm(Cols0, Code0, _, _), Cols, Code) :-
    reverse(Cols0, Cols), reverse(Code0, Code),
    Code \== [].

vm_bind(C-P, vm(Cs0, Code0, Env0, N0), vm(Cs, Code, Env, N)) :- !,
    vm_column(C, Cs0, Cs, J),
    (   var(P)
    ->  Vs = [P]
    ;   tuple_of_vars(P, Vs)
    ),
    length(Vs, K),
    foldl(vm_load(J, K), Vs, 0-(Code0-Env0-N0), _-(Code-Env-N)).
vm_bind('$e'(W, Ex, _), S0, vm(Cs, Code, [W-R-F|Env], N)) :-
    vm_expr(Ex, R, F, S0, vm(Cs, Code, Env, N)).

vm_load(J, K, V, Comp-(Code0-Env0-N0), Comp1-([ld(N0, J, Comp, K)|Code0]-[V-N0-true|Env0]-N)) :-
    Comp1 is Comp+1, N is N0+1, N < 64.

vm_column(C, Cs, Cs, J) :-
    nth0(J0, Cs, C0), C0 == C, !,
    length(Cs, L), J is L-1-J0.
vm_column(C, Cs, [C|Cs], J) :-
    length(Cs, J), J < 32.

%   vm_expr(+Ex, -R, -Float, +S0, -S): Ex computed into register R.
vm_expr(X, R, F, S, S) :-
    var(X), !,
    S = vm(_, _, Env, _),
    member(V-R0-F0, Env), V == X, !,
    R = R0, F = F0.
vm_expr(X, R, F, vm(Cs, Code, Env, R), vm(Cs, [cst(R, X)|Code], Env, N)) :-
    number(X), !,
    ( float(X) -> F = true ; F = false ),
    N is R+1, N < 64.
vm_expr(X, R, true, vm(Cs, Code, Env, R), vm(Cs, [cst(R, V)|Code], Env, N)) :-
    atom(X), memberchk(X-V, [pi-3.141592653589793, e-2.718281828459045]), !,
    N is R+1, N < 64.
vm_expr(X, R, F, S0, vm(Cs, [op(R, *, RA, RA)|Code], Env, N)) :-
    compound(X), X = A**B, B == 2, !,             % (A*A: the same float as A**2)
    vm_expr(A, RA, F, S0, vm(Cs, Code, Env, R)),
    N is R+1, N < 64.
vm_expr(X, R, F, S0, vm(Cs, [op(R, Op, RA, RB)|Code], Env, N)) :-
    compound(X), X =.. [Op0, A, B],
    memberchk(Op0-Op, [(+)-(+), (-)-(-), (*)-(*), (/)-(/), (**)-(**), atan2-atan2,
                       atan-atan2]), !,
    vm_expr(A, RA, FA, S0, S1),
    vm_expr(B, RB, FB, S1, vm(Cs, Code, Env, R)),
    (   memberchk(Op, [atan2]) -> F = true
    ;   ( FA == true ; FB == true ) -> F = true
    ;   F = false
    ),
    N is R+1, N < 64.
vm_expr(X, R, F, S0, vm(Cs, [fn(R, Fn, RA)|Code], Env, N)) :-
    compound(X), X =.. [Fn, A],
    memberchk(Fn, [-, sqrt, exp, log, sin, cos, tan, atan, tanh, abs]), !,
    vm_expr(A, RA, FA, S0, vm(Cs, Code, Env, R)),
    (   memberchk(Fn, [-, abs]) -> F = FA ; F = true ),
    N is R+1, N < 64.

%!  compiled_instance(+Ps:list(integer), +Binds, +Tmpl, !C) is det.
%
%   Each particle of Ps whose value in column C is not drawn yet ('$u')
%   gets its instance of Tmpl (plan/3), by a compiled loop (see
%   compiled_test/4; ddc_batch_rv:instance_each/4 is the same without
%   one).
compiled_instance(Ps, Bs, Tmpl, C) :-
    col_backend(foreign),
    vm_instance(Ps, Bs, Tmpl, C), !.
compiled_instance(Ps, Bs, Tmpl, C) :-
    bind_goals(Bs, I, Cs, CVs, Gets, Evals),
    append(Gets, Evals, Gs0),
    conj_from_list(Gs0, Cond1),
    abstract_numbers(Cond1-Tmpl, Cond-Value, Ks),
    pairs_keys_values(Ks, KVs, Ns),
    Head =.. [cols|CVs],
    compiled_loop(instance(Value), Head, k(KVs), I, Cond, Name),
    Cols =.. [cols|Cs],
    ps_list(Ps, L),
    call(Name, L, Cols, k(Ns), C).

%   compiled_loop(+Kind, +Head, +Consts, ?I, +Cond, -Name): the loop
%   predicate Name/4 for this shape (Name(Ps, Cols, Consts, Out)), made the
%   first time (under a mutex: threads share it).
compiled_loop(Kind, Head, Consts, I, Cond, Name) :-
    Shape = loop(Kind, Head, Consts, I, Cond),
    variant_sha1(Shape, Sha),
    atom_concat('$b_loop_', Sha, Name),
    (   '$b_loop_ready'(Name)
    ->  true
    ;   with_mutex('$ddc_batch_loops',
                   (   '$b_loop_ready'(Name) -> true
                   ;   copy_term(Shape, loop(Kind1, Head1, Consts1, I1, Cond1)),
                       loop_clauses(Kind1, Name, Head1, Consts1, I1, Cond1, Clauses),
                       optimised(forall(member(C, Clauses), assertz(C))),
                       compile_predicates([Name/4]),
                       assertz('$b_loop_ready'(Name))   % (last: another thread may look)
                   ))
    ).

:- dynamic '$b_loop_ready'/1.

loop_clauses(test, Name, Head, Consts, I, Cond,
             [ Base, (Rec :- ( Cond -> Out = [I|Out1] ; Out = Out1 ), Next) ]) :-
    Base =.. [Name, [], _, _, []],
    Rec =.. [Name, [I|Is], Head, Consts, Out],
    Next =.. [Name, Is, Head, Consts, Out1].
loop_clauses(instance(Value), Name, Head, Consts, I, Cond,
             [ Base, (Rec :- ( IsU, Cond -> SetArg ; true ), Next) ]) :-
    is_u_goal(I, Out, IsU),
    setarg_goal(I, Out, Value, SetArg),
    Base =.. [Name, [], _, _, _],
    Rec =.. [Name, [I|Is], Head, Consts, Out],
    Next =.. [Name, Is, Head, Consts, Out].

%   abstract_numbers(+T, -T1, -Pairs): T with each number a variable;
%   Pairs the Variable-Number pairs, in order.
abstract_numbers(T, T1, Ps) :-
    map_term(number_leaf, T, T1, Ps, []).

number_leaf(T, V, [V-T|Ps], Ps) :- number(T).

%   bind_goals(+Binds, ?I, -Columns, -ColumnVars, -Gets, -Evals): the goals
%   that bind/2 runs for particle I, each column a variable (a clause must
%   not hold a column: asserting it would copy it).
bind_goals([], _, [], [], [], []).
bind_goals([C-P|Bs], I, [C|Cs], [CV|CVs], [Arg|Gs], Es) :- !,
    arg_goal(I, CV, P, Arg),
    bind_goals(Bs, I, Cs, CVs, Gs, Es).

bind_goals(['$e'(W, Ex, _)|Bs], I, Cs, CVs, Gs, [W is Ex|Es]) :-
    bind_goals(Bs, I, Cs, CVs, Gs, Es).

%   arg_goal(?I, ?C, ?V, -G), is_u_goal(?I, ?C, -G), setarg_goal(?I, ?C,
%   ?V, -G): a compiled loop's goals that read and write a column: with
%   columns as terms, the builtins themselves (compiled inline).
arg_goal(I, C, V, G) :-
    (   col_backend(prolog) -> G = arg(I, C, V) ; G = col_arg(I, C, V) ).

is_u_goal(I, C, G) :-
    (   col_backend(prolog) -> G = (arg(I, C, U), U == '$u') ; G = col_is_u(I, C) ).

setarg_goal(I, C, V, G) :-
    (   col_backend(prolog) -> G = nb_setarg(I, C, V) ; G = col_setarg(I, C, V) ).

test_each([], _, _, []).
test_each([I|Is], Bs, G, Ps) :-
    (   \+ \+ ( bind(Bs, I), call(G) ) -> Ps = [I|Ps1] ; Ps = Ps1 ),
    test_each(Is, Bs, G, Ps1).

%!  partition_batch(+T, +Ps0:list(integer), -T1, -Ps:list(integer)) is nondet.
%
%   T1 is T with its column references replaced by
%   the particles' values, for each group of particles that share them.
%   (Only the columns' values are grouped: T's own unbound variables stay
%   T1's, for the goals after it.)
partition_batch(T0, Ps0, T1, Ps) :-
    (   has_column(T0)
    ->  materialise(T0, Ps0, T),
        plan(T, Tmpl, Bs),
        pairs_keys_values(Bs, Cs, Pats),
        groups_by_values(Ps0, Cs, Groups),
        member(Pats-Ps, Groups),
        T1 = Tmpl
    ;   T1 = T0, Ps = Ps0
    ).

%!  groups_by_values(+Ps, +Columns, -Groups) is det.
%
%   Vs-Ps pairs, the particles
%   of Ps grouped by their values Vs in Columns, in the standard order of
%   Vs (each group's particles in the order of Ps).
groups_by_values(Ps, Cs, Groups) :-
    col_backend(foreign),
    col_partition(Ps, Cs, Groups0), !,
    keysort(Groups0, Groups).
groups_by_values(Ps0, Cs, Groups) :-
    ps_list(Ps0, Ps),
    value_pairs(Ps, Cs, Pairs),
    keysort(Pairs, Sorted),
    group_pairs_by_key(Sorted, Groups).

value_pairs([], _, []).
value_pairs([I|Is], Cs, [Vs-I|Ps]) :-
    args_at(Cs, I, Vs),
    value_pairs(Is, Cs, Ps).

args_at([], _, []).
args_at([C|Cs], I, [V|Vs]) :- col_arg(I, C, V), args_at(Cs, I, Vs).

%!  unify_value(?P, +V, +Ps0:list(integer), -Ps:list(integer)) is semidet.
%
%   P unified with a value the batch agrees on (over columns: Ps the
%   particles where it unifies).
unify_value(P, V, Ps, Ps) :-
    (   has_column(P)
    ->  fail
    ;   P = V -> true
    ;   number(P), number(V), P =:= V
    ), !.
unify_value(P, V, Ps0, Ps) :-
    has_column(P),
    test_loop(P = V, Ps0, Ps).

%!  unify_column(?P, +C, +Ps0:list(integer), -Ps:list(integer)) is nondet.
%!  unify_column(?P, +C, +Arity, +Ps0:list(integer), -Ps:list(integer)) is nondet.
%
%   P unified with each particle's value in column C (none undefined), Ps
%   the particles of a branch; Arity: the tuple arity all values in C
%   have (a number), unknown or none.
unify_column(P, C, Ps0, Ps) :-
    unify_column(P, C, unknown, Ps0, Ps).

unify_column(P, C, Arity, Ps0, Ps) :-
    (   var(P)
    ->  column_ref(C, _, P), Ps = Ps0
    ;   tuple_of_vars(P, Vs)
    ->  length(Vs, K),
        (   Arity == K -> Ps = Ps0 ; with_arity(Ps0, C, K, Ps), Ps \== [] ),
        copy_term(P, Pat),
        term_variables(Pat, PVs),
        maplist(element_ref(C, Pat), Vs, PVs)
    ;   ground(P), \+ has_column(P)
    ->  (   col_select_unify(Ps0, C, P, Ps1) -> Ps = Ps1
        ;   ps_list(Ps0, L), with_value(L, C, P, Ps)
        ),
        Ps \== []
    ;   plan(P, Tmpl, Bs),
        ps_list(Ps0, L),
        unifiable_at(L, C, Bs, Tmpl, Ps1),
        Ps1 \== [],
        partition_column(C, Ps1, V, Ps),
        unify_value(P, V, Ps, _)
    ).

element_ref(C, Pat, V, PV) :- V = '$c'(C, Pat, PV).

with_arity(Ps0, C, K, Ps) :-
    col_with_arity(Ps0, C, K, Ps1), !,
    Ps = Ps1.
with_arity(Ps0, C, K, Ps) :-
    tuple_shape(K, Shape),
    ps_list(Ps0, L),
    with_shape(L, C, Shape, Ps).

with_shape([], _, _, []).
with_shape([I|Is], C, Shape, Ps) :-
    col_arg(I, C, V),
    (   subsumes_term(Shape, V), V \== '$undef', V \== '$u' -> Ps = [I|Ps1] ; Ps = Ps1 ),
    with_shape(Is, C, Shape, Ps1).

with_value([], _, _, []).
with_value([I|Is], C, P, Ps) :-
    col_arg(I, C, V),
    (   ( V = P -> true ; number(V), number(P), V =:= P ) -> Ps = [I|Ps1] ; Ps = Ps1 ),
    with_value(Is, C, P, Ps1).

unifiable_at([], _, _, _, []).
unifiable_at([I|Is], C, Bs, Tmpl, Ps) :-
    col_arg(I, C, V),
    (   \+ \+ ( bind(Bs, I), Tmpl = V ) -> Ps = [I|Ps1] ; Ps = Ps1 ),
    unifiable_at(Is, C, Bs, Tmpl, Ps1).

%!  partition_column(+C, +Ps0:list(integer), -V, -Ps:list(integer)) is nondet.
%
%   For each value V that particles of Ps0 hold in column C, Ps those
%   particles (in the standard order of the values).
partition_column(C, Ps0, V, Ps) :-
    groups_by_values(Ps0, [C], Groups),
    member([V]-Ps, Groups).

%!  tuple_of_vars(@P, -Vs:list) is semidet.
%
%   P is a tuple of two or more distinct
%   variables Vs (a pattern such as (X, Y, Z) or (_, _, Z)).
tuple_of_vars(P, [A|Vs]) :-
    nonvar(P), P = (A, B), var(A),
    tuple_vars(B, Vs),
    term_variables(P, All), length(All, K), length([A|Vs], K).

tuple_vars(P, [P]) :- var(P), !.
tuple_vars((A, B), [A|Vs]) :- var(A), tuple_vars(B, Vs).

