/*  plunit tests: a uniform over an integer range is drawn and weighed from the
    range itself (a constant list Lo, Lo+1, ..., Hi, or a findall-between list
    used only as the support), with the same draws, masses and errors as the
    list it stands for.
*/
:- use_module('../../prolog/ddc').
:- use_module(library(plunit)).
:- use_module(library(lists)).

program(Lines, M) :-
    tmp_file_stream(text, File, S),
    forall(member(L, Lines), format(S, "~w~n", [L])),
    close(S),
    ddc_load(File, M).

%   A list built at run time by unification is not a range: the reference.
range_program(M) :-
    program([ 'a ~ uniform([3,4,5,6]).',
              'b ~ uniform(L) := findall(I, between(3, 6, I), L).',
              'c ~ uniform(L) := L = [3,4,5,6].',
              'd ~ uniform([6,5,4,3]).',
              'n ~ val(0).',
              'e ~ uniform(L) := n ~= N, findall(I, between(1, N, I), L).',
              'f ~ uniform(L) := findall(I, between(1, 3, I), L), length(L, 3).'
            ], M).

draws(M, X, Seed, Vs) :-
    set_random(seed(Seed)),
    findall(V, ( between(1, 40, _), ddc_sample_world(M, X ~= V, [], _) ), Vs).

:- begin_tests(ddc_ranges).

test(same_draws_as_the_list) :-
    range_program(M),
    draws(M, c, 5, C), draws(M, a, 5, A), draws(M, b, 5, B),
    A == C, B == C,
    sort(C, Values), Values == [3, 4, 5, 6].

test(same_masses_as_the_list) :-
    range_program(M),
    forall(member(X, [a, b, c, d]),
           ( query(X ~= 5, P, [samples(20), program(M)]), abs(P - 0.25) < 1.0e-12,
             query(X ~= 7, P0, [samples(20), program(M)]), P0 =:= 0.0,
             query(X ~= 5.0, P1, [samples(20), program(M)]), abs(P1 - 0.25) < 1.0e-12 )).

test(empty_range_is_an_error, Cause == empty_support) :-
    range_program(M),
    catch(query(e ~= 1, _, [samples(5), program(M)]),
          error(ddc(distribution(_, Cause), _), _), true).

test(list_used_elsewhere_stays_a_list) :-
    range_program(M),
    query(f ~= 2, P, [samples(20), program(M)]),
    abs(P - 1/3) < 1.0e-12.

test(ranges_are_compiled_as_ranges) :-
    range_program(M),
    forall(member(X-Kind, [a-range, b-range, c-list, d-list, f-list]),
           ( once(M:'$rv'(X, u, _, 0, none, Out, _, _, _)),
             ( Out = '$chk'(D, _) -> true ; D = Out ),
             ( D = uniform(_:_) -> Kind == range ; Kind == list ) )).

:- end_tests(ddc_ranges).
