/*  Tests of the batched filter's columns (prolog/ddc/batch/ddc_batch_col.pl) and of
    the engine's loops over them: the same answers from the compiled
    column library and from the Prolog terms (DDC_COLUMNS=prolog runs this
    file with the library not loaded; tests/test_plunit.py runs it both
    ways).

        swipl -g run_tests -t halt tests/prolog/batch/test_ddc_batch_col.pl
*/

:- use_module(library(plunit)).
:- use_module(library(lists)).
:- use_module(library(apply)).
:- use_module('../../../prolog/ddc').
:- use_module('../../../prolog/ddc/batch/ddc_batch_col').
:- use_module('../../../prolog/ddc/batch/ddc_batch_columns').
:- use_module('../../../prolog/ddc/lang/ddc_ops').
:- use_module('../../../prolog/ddc/batch/ddc_batch_rv').
:- use_module(library(aggregate)).

:- begin_tests(ddc_batch_col).

values([ '$u', '$undef', a, 'hello world', 1.5, (1.0, 2.0, 3.0), (1, 2, 3), 7, -0.0,
         [a, b], [], f(X, X, _), "text", (1.0, 2.0), (a, 1.0) ]).

test(every_value_reads_back_as_written) :-
    values(Vs),
    length(Vs, N),
    col_new(N, '$u', C),
    forall(nth1(I, Vs, V), col_setarg(I, C, V)),
    col_list(C, Back),
    maplist(=@=, Vs, Back),
    col_size(C, N).

test(a_write_replaces_the_value_and_survives_backtracking) :-
    col_new(3, none, C),
    \+ ( col_setarg(2, C, (0.5, 0.25, 0.125)), fail ),
    col_arg(2, C, V), V == (0.5, 0.25, 0.125),
    col_setarg(2, C, other), col_arg(2, C, W), W == other,
    col_arg(1, C, none).

test(status_of_a_column) :-
    col_from_list([a, a, a], C1), col_status(C1, S1), S1 == same(a),
    col_from_list([1.0, 2.0], C2), col_status(C2, S2), S2 == defined,
    col_from_list([1.0, '$undef'], C3), col_status(C3, S3), S3 == mixed,
    col_from_list([1.0, '$u'], C4), col_status(C4, S4), S4 == open,
    col_from_list(['$undef', '$undef'], C5), col_status(C5, S5), S5 == same('$undef'),
    col_from_list([[x], [x]], C6), col_status(C6, S6), S6 == same([x]).

test(batches_not_drawn_defined_and_set) :-
    col_from_list(['$u', a, '$undef', '$u', (1.0, 2.0)], C),
    col_uncomputed([1, 2, 3, 4, 5], C, U), U == [1, 4],
    col_defined_at([1, 2, 3, 4, 5], C, D), D == [2, 5],
    col_set_each([2, 4], C, z),
    col_list(C, L), L == ['$u', a, '$undef', z, (1.0, 2.0)],
    col_all_same([2], C, 2),
    \+ col_all_same([2, 4], C, 2).

test(gather_from_groups) :-
    col_from_list([a, (1.0, 2.0), [x]], C1),
    col_from_list([b, c], C2),
    col_gather([C1, '$none', C2], [3-2, 1-3, 2-1, 1-1, 1-2], C),
    col_list(C, L), L == [c, [x], '$u', a, (1.0, 2.0)].

test(partitions_in_the_standard_order_of_the_values) :-
    col_from_list([b, a, c, a, b, (1.0, 2.0)], C1),
    col_from_list([1.0, 1.0, 1.0, 2.0, 1.0, 1.0], C2),
    findall(V-Ps, partition_column(C1, [1, 2, 3, 4, 5, 6], V, Ps), G1),
    G1 == [a-[2, 4], b-[1, 5], c-[3], (1.0, 2.0)-[6]],
    findall(T-Ps, partition_batch('$c'(C1, V1, V1)-'$c'(C2, V2, V2), [1, 2, 3, 4, 5], T, Ps), G2),
    G2 == [(a-1.0)-[2], (a-2.0)-[4], (b-1.0)-[1, 5], (c-1.0)-[3]].

test(a_comparison_over_tuples) :-
    col_from_list([(0.0, 0.0, 0.1), (0.5, 0.0, 0.1), (0.1, 0.1, 0.3), '$undef'], CA),
    col_from_list([(0.0, 0.0, 0.2), (0.0, 0.0, 0.2), (0.0, 0.0, 0.2), '$undef'], CB),
    P = (X, Y, Z), Q = (XB, YB, ZB),
    R1 = '$c'(CA, P, X), R2 = '$c'(CA, P, Y), R3 = '$c'(CA, P, Z),
    S1 = '$c'(CB, Q, XB), S2 = '$c'(CB, Q, YB), S3 = '$c'(CB, Q, ZB),
    test_loop(sqrt((R1-S1)**2 + (R2-S2)**2) < 0.3, [1, 2, 3], Near), Near == [1, 3],
    test_loop(R3 < S3, [1, 2, 3], Below), Below == [1, 2],
    %   (16 particles or more: the compiled loop)
    numlist(1, 40, Is),
    findall((V, 0.0, 0.0), ( member(I, Is), V is I/40 ), Vs),
    col_from_list(Vs, CV),
    test_loop('$c'(CV, (A, _, _), A) >= 0.5, Is, Half),
    numlist(20, 40, Half).

test(arithmetic_errors_are_prolog_errors, error(evaluation_error(zero_divisor))) :-
    numlist(1, 20, Is),
    findall((0.0, 1.0), member(_, Is), Vs),
    col_from_list(Vs, C),
    test_loop(1.0 / '$c'(C, (A, _), A) > 0.0, Is, _).

test(a_tuple_computed_from_columns) :-
    numlist(1, 20, Is),
    findall((X, 0.5, 1.0), ( member(I, Is), X is I*0.25 ), Vs),
    col_from_list(Vs, C),
    P = (X0, Y0, Z0),
    RX = '$c'(C, P, X0), RY = '$c'(C, P, Y0), RZ = '$c'(C, P, Z0),
    arith_value(W1, RX + 1.0, Is, _), arith_value(W2, RY * RZ, Is, _),
    arith_value(W3, sqrt(RX), Is, _),
    plan((W1, W2, W3), Tmpl, Bs),
    col_new(20, '$u', Out),
    col_setarg(3, Out, kept),
    compiled_instance(Is, Bs, Tmpl, Out),
    col_list(Out, Back),
    forall(( nth1(I, Back, V), I =\= 3 ),
           ( W is I*0.25 + 1.0, S is sqrt(I*0.25), V == (W, 0.5, S) )),
    nth1(3, Back, kept).

test(a_template_is_instantiated_not_evaluated) :-
    numlist(1, 20, Is),
    findall(X, ( member(I, Is), X is I*0.5 ), Vs),
    col_from_list(Vs, C),
    plan(('$c'(C, A, A), 1, A+1.0), Tmpl, Bs),
    col_new(20, '$u', Out),
    compiled_instance(Is, Bs, Tmpl, Out),
    col_arg(4, Out, V), V == (2.0, 1, 2.0+1.0).

test(lists_appended_to_and_without_repeats) :-
    col_from_list([[], [a], [], [b, c]], C),
    (   col_append_each([1, 2, 4], C, x) -> true ; collect_append([1, 2, 4], C, x) ),
    (   col_append_each([2], C, f(y)) -> true ; collect_append([2], C, f(y)) ),
    col_list(C, L), L == [[x], [a, x, f(y)], [], [b, c, x]],
    col_from_list([[a, b, a], [c], [d, d]], D),
    col_new(3, '$u', S),
    (   col_sets_each([1, 2, 3], D, S) -> true
    ;   forall(between(1, 3, I), ( col_arg(I, D, X), list_to_set(X, Y), col_setarg(I, S, Y) ))
    ),
    col_list(S, LS), LS == [[a, b], [c], [d]].

collect_append(Ps, C, V) :-
    forall(member(I, Ps), ( col_arg(I, C, L0), append(L0, [V], L1), col_setarg(I, C, L1) )).

test(particles_whose_value_unifies) :-
    col_from_list([true, false, 1, 1.0, f(_), '$undef', [a]], C),
    Ps = [1, 2, 3, 4, 5, 6, 7],
    findall(P-Out, ( member(P, [true, 1, f(z), [a]]),
                     unify_column(P, C, Ps, Out) ), Pairs),
    Pairs == [true-[1], 1-[3, 4], f(z)-[5], [a]-[7]].

test(uniform_draws_from_lists_of_atoms) :-
    numlist(1, 400, Is),
    findall([a, b, c, d], member(_, Is), Ls),
    col_from_list(Ls, LC),
    unify_column(L, LC, Is, _),
    col_new(400, '$u', Out),
    set_random(seed(3)),
    assign(Is, Out, uniform(L)),
    col_list(Out, Vs),
    forall(member(V, [a, b, c, d]),
           ( aggregate_all(count, member(V, Vs), K), K > 60, K < 140 )).

test(finite_draws_with_probabilities_over_the_batch) :-
    numlist(1, 1000, Is),
    findall(P, ( member(I, Is), P is (I mod 2) * 0.8 + 0.1 ), Ps),
    col_from_list(Ps, PC),
    unify_column(P1, PC, Is, _),
    arith_value(P2, 1 - P1, Is, _),
    col_new(1000, '$u', Out),
    set_random(seed(5)),
    assign(Is, Out, finite([P1:yes, P2:no])),
    col_list(Out, Vs),
    aggregate_all(count, ( nth1(I, Vs, yes), I mod 2 =:= 1 ), Odd),
    aggregate_all(count, ( nth1(I, Vs, yes), I mod 2 =:= 0 ), Even),
    abs(Odd - 450) < 60, abs(Even - 50) < 30.

%   The library's gaussian draws (its standard normals: a ziggurat) have the
%   normal's moments and tails, within five standard errors of 100,000
%   draws.
test(gaussian_draws_have_the_normals_moments_and_tails) :-
    (   col_backend(foreign)
    ->  N = 100000,
        col_new(N, (1.0, -2.0, 0.0), M), col_new(N, '$u', Out), ps_all(N, All),
        col_draw_gauss(All, M, chol(2.0, 0.0, 1.0, 0.0, 0.0, 1.0), Out, 42),
        col_list(Out, Vs),
        findall(Z, ( member((X, _, _), Vs), Z is (X - 1.0)/2.0 ), Zs),
        findall(Z, ( member((_, Y, _), Vs), Z is Y + 2.0 ), Ws),
        forall(member(S, [Zs, Ws]),
               (   moments(S, N, Mean, Var, Kurt),
                   abs(Mean) < 5*sqrt(1/N), abs(Var - 1) < 5*sqrt(2/N),
                   abs(Kurt - 3) < 5*sqrt(96/N),
                   forall(member(T-P, [1-0.31731, 2-0.04550, 3-0.0026998, 3.5-0.00046527]),
                          (   aggregate_all(count, ( member(Z, S), abs(Z) > T ), K),
                              abs(K/N - P) < 5*sqrt(P*(1-P)/N)
                          ))
               ))
    ;   true
    ).

moments(S, N, Mean, Var, Kurt) :-
    sum_list(S, S1), Mean is S1/N,
    foldl([Z, A0, A]>>(A is A0 + (Z-Mean)**2), S, 0.0, S2), Var is S2/N,
    foldl([Z, A0, A]>>(A is A0 + (Z-Mean)**4), S, 0.0, S4), Kurt is S4/N/(Var*Var).

%   A column whose particles all hold one value (the library keeps one cell
%   for it) reads and writes as any other: a write to some particles gives
%   them their own values.
test(a_column_of_one_value_reads_and_writes_as_any_other) :-
    col_new(5, '$u', C),
    col_set_each([1, 2, 3, 4, 5], C, (1.0, 2.0)),
    col_status(C, S0), S0 == same((1.0, 2.0)),
    col_arg(3, C, V3), V3 == (1.0, 2.0),
    col_all_same([1, 4], C, 2),
    findall(V-Ps, partition_column(C, [1, 2, 5], V, Ps), G0), G0 == [(1.0, 2.0)-[1, 2, 5]],
    col_gather([C, C], [2-5, 1-1], G), col_list(G, GL), GL == [(1.0, 2.0), (1.0, 2.0)],
    col_setarg(2, C, x),
    col_list(C, L), L == [(1.0, 2.0), x, (1.0, 2.0), (1.0, 2.0), (1.0, 2.0)],
    col_status(C, S1), S1 == defined,
    col_new(4, [], LC),
    (   col_append_each([1, 2, 3, 4], LC, a) -> true ; collect_append([1, 2, 3, 4], LC, a) ),
    col_status(LC, S2), S2 == same([a]),
    (   col_append_each([2], LC, b) -> true ; collect_append([2], LC, b) ),
    col_list(LC, LL), LL == [[a], [a, b], [a], [a]],
    col_new(3, [x, y, x], D), col_new(3, '$u', Set),
    (   col_sets_each([1, 2, 3], D, Set) -> true
    ;   forall(between(1, 3, I), ( col_arg(I, D, X), list_to_set(X, Y), col_setarg(I, Set, Y) ))
    ),
    col_list(Set, SL), SL == [[x, y], [x, y], [x, y]],
    col_new(3, '$u', U), col_set_each([2], U, z), col_list(U, UL), UL == ['$u', z, '$u'].

%   Rows of floats straight from columns (the library only; the Prolog
%   columns fail, and the caller makes the rows from the values).
test(columns_read_as_rows_of_floats) :-
    (   col_backend(foreign)
    ->  col_from_list([(1.0, 2.0), '$undef', (3.0, 4.0)], C1),
        col_from_list(['$u', (5.0, 6.0)], C2),
        col_row_width(C1, 2), col_row_width(C2, 2),
        col_rows(C1, W, Fs, []), W == 2,
        Fs = [A, B, X, Y, E, F], A-B-E-F == 1.0-2.0-3.0-4.0, X =\= X, Y =\= Y,
        col_pack_rows([C1, C2], 2, Rows),
        col_floats_list(Rows, L), length(L, 10),
        append(Fs, [U, V, 5.0, 6.0], L0), L0 = L, U =\= U, V =\= V,
        \+ col_floats_into(Rows, 1, 9, _),         % (too little room: nothing copied)
        col_from_list([a, (1.0, 2.0)], C3), \+ col_row_width(C3, _),
        \+ col_rows(C3, _, _, []), \+ col_pack_rows([C3], 2, _),
        col_from_list(['$undef'], C4), col_row_width(C4, 0), \+ col_rows(C4, _, _, [])
    ;   col_from_list([(1.0, 2.0)], C), \+ col_rows(C, _, _, [])
    ).

%   A partition binds a reference's pattern to its branch's value: the reference
%   is ground, and still reads its column (a goal after the partition filters by
%   it).
test(a_reference_made_ground_by_a_partition_still_reads_its_column) :-
    col_from_list([a, b, a], C),
    R = '$c'(C, V, V),
    once(partition_batch(R, [1, 2, 3], T, Ps)),
    T == a, Ps == [1, 3], ground(R),
    has_column(R).

:- end_tests(ddc_batch_col).
