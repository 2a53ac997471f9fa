/*  plunit tests of the DDC system (prolog/ddc.pl): language, inference,
    errors, loading, and the particle-filter API.  Probabilistic checks use
    fixed seeds and tolerances of about 5 standard errors.
*/
:- use_module('../../prolog/ddc').
:- use_module(library(plunit)).
:- use_module(library(lists)).
:- use_module(library(apply)).

example(Name, File) :-
    source_file(example(_, _), This),
    file_directory_name(This, Dir),
    atomic_list_concat([Dir, '/../../prolog/examples/', Name, '.pl'], File0),
    absolute_file_name(File0, File).

%   program(+Lines, -File): a DC program in a temporary file.
program(Lines, File) :-
    tmp_file_stream(text, File, S),
    forall(member(L, Lines), format(S, "~w~n", [L])),
    close(S).

load_text(Lines, M) :-
    program(Lines, F),
    ddc_load(F, M).

close_to(P, Exact, Tol) :-
    (   abs(P - Exact) =< Tol -> true
    ;   format(user_error, "~w is not within ~w of ~w~n", [P, Tol, Exact]), fail
    ).

%   error_at(+Goal, -Cause, -Line): Goal throws a ddc error at a line, or the reader's
%   (ddc_source.pl: a file that cannot be read, Cause its ISO formal term).
error_at(G, Cause, Line) :-
    catch((G, Cause = none, Line = 0), error(Formal, Ctx), true),
    (   var(Formal) -> true
    ;   Formal = ddc(Cause, Where) -> true
    ;   Ctx = context(ddc_source:_, Where) -> Cause = Formal
    ;   throw(error(Formal, Ctx))
    ),
    (   nonvar(Where), Where = _:Line0 -> Line = Line0 ; true ).

:- begin_tests(ddc_language).

test(weighted_ground_query_is_exact) :-
    example(tutorial, F), ddc_load(F),
    query(coin ~= true, P, [samples(200), seed(1)]),
    close_to(P, 0.2, 1.0e-9).

test(sampled_query_within_tolerance) :-
    example(tutorial, F), ddc_load(F),
    query(true, (nballs ~= N, N > 5), P, [samples(4000), seed(2), stderr(SE)]),
    SE > 0, SE < 0.02,
    close_to(P, 0.5, 5*SE).

test(same_seed_same_answer) :-
    example(tutorial, F), ddc_load(F),
    Q = (drawn(1) ~= X, color(X) ~= black),
    query(true, Q, P1, [samples(500), seed(42)]),
    query(true, Q, P2, [samples(500), seed(42)]),
    P1 == P2,
    query(true, Q, P3, [samples(500), seed(43)]),
    P1 \== P3.

test(variable_sampled_inside_negation_stays) :-
    load_text(['x ~ finite([0.5:a, 0.5:b]).'], M),
    query(true, (\+ x ~= a, x ~= a), P, [samples(300), seed(3), program(M)]),
    P =:= 0.0,
    query(true, (\+ x ~= a, x ~= b), P2, [samples(300), seed(3), program(M)]),
    close_to(P2, 0.5, 0.15).

test(undefined_variable) :-
    load_text(['c ~ finite([0.5:t, 0.5:f]).', 'h ~ val(1) := c ~= t.'], M),
    query(true, \+ h ~= _, P, [samples(2000), seed(4), program(M), stderr(SE)]),
    close_to(P, 0.5, 5*SE).

test(true_is_a_fresh_flip_each_call) :-
    load_text(['a ~ val(1).'], M),
    query(true, (true(0.5), true(0.5)), P, [samples(4000), seed(5), program(M), stderr(SE)]),
    close_to(P, 0.25, 5*SE).

test(impure_derived_atom_is_memoised) :-
    load_text(['f := true(0.5).'], M),
    query(true, (f, f), P, [samples(4000), seed(6), program(M), stderr(SE)]),
    close_to(P, 0.5, 5*SE),
    query(true, (f, \+ f), P0, [samples(500), seed(6), program(M)]),
    P0 =:= 0.0.

test(arithmetic_parameters_and_paper_sugar) :-
    load_text(['x ~ uniform(0, 10).', 'y ~ gaussian(X + 3, 0.25) := x ~= X.',
               'z ~ finite(0.25:a, 0.75:b).'], M),
    expectation(true, (x ~= X, y ~= Y, D is Y - X), D, E, [samples(3000), seed(7), program(M), stderr(SE)]),
    close_to(E, 3.0, 5*SE),
    query(z ~= b, P, [samples(10), program(M)]),
    close_to(P, 0.75, 1.0e-9).

test(builtin_and_plain_prolog_helpers) :-
    load_text(['twice(X, Y) :- Y is 2*X.', 'n ~ uniform([1,2,3]).',
               'big := n ~= N, twice(N, M), M > 3.'], M),
    query(big, P, [samples(3000), seed(8), program(M), stderr(SE)]),
    close_to(P, 2/3, 5*SE).

test(findall_forward_over_dc_goal) :-
    load_text(['n ~ val(3).', 'c(I) ~ finite([0.5:on, 0.5:off]) := n ~= N, between(1, N, I).',
               'count(K) := findall_forward(I, (between(1, 3, I), c(I) ~= on), L), length(L, K).'], M),
    distribution(true, count(K), K, D, [samples(4000), seed(9), program(M)]),
    memberchk(P0:0, D), close_to(P0, 0.125, 0.03),
    memberchk(P3:3, D), close_to(P3, 0.125, 0.03).

test(non_ground_read_enumerates_defined_variables) :-
    example(graph, F), ddc_load(F),
    query(true, p(1, 5), P, [samples(4000), seed(10), stderr(SE)]),
    close_to(P, 0.25, 5*SE),
    query(true, path(1, 5), P2, [samples(10)]),
    P2 =:= 1.0.

test(logistic_and_linear) :-
    logistic([0.05], [-16.9, 0.8], P),
    Exact is 1/(1+exp(-(0.8 - 16.9*0.05))),
    close_to(P, Exact, 1.0e-12),
    linear([1, 2], [0.5, 0.25, 1.0], Y),
    close_to(Y, 2.0, 1.0e-12),
    %   (a linear/3 that succeeds leaves Why = succeeded: the test fails)
    catch(( linear([1], [1.0], _), Why = succeeded ), error(domain_error(Why, _), _), true),
    Why == weights_one_more_than_inputs(1).

test(logistic_in_a_clause) :-
    load_text(['d ~ val(0.0).', 'o ~ finite([P:true, Q:false]) := d ~= D, logistic([D], [-16.9, 0.8], P), Q is 1 - P.'], M),
    query(o ~= true, P, [samples(5), program(M)]),
    Exact is 1/(1+exp(-0.8)),
    close_to(P, Exact, 1.0e-9).

test(time_unrolled_static_query) :-
    load_text(['x:0 ~ val(0.0).', 'x:t+1 ~ gaussian(X + 1, 0.01) := x:t ~= X.'], M),
    expectation(true, x:3 ~= V, V, E, [samples(500), seed(11), program(M), stderr(SE)]),
    close_to(E, 3.0, 5*SE + 1.0e-9),
    expectation(true, x:t ~= V2, V2, E2, [samples(500), seed(11), program(M), time(2)]),
    close_to(E2, 2.0, 0.05),
    query(true, x:2 > 1.0, P, [samples(500), seed(12), program(M)]),
    P =:= 1.0.

test(query5_and_query8_original_forms) :-
    example(tutorial, F), ddc_load(F),
    query([], [], (nballs ~= N, N > 5), 2000, P),
    close_to(P, 0.5, 0.06),
    query([nballs ~= 3], [], material(1) ~= wood, 1000, P2),
    close_to(P2, 0.3, 1.0e-9),
    query([], [], nballs ~= X, X, 3000, Avg, _, _),
    close_to(Avg, 5.5, 0.25).

:- end_tests(ddc_language).

:- begin_tests(ddc_evidence).

test(likelihood_weighting_gaussian) :-
    example(example1, F), ddc_load(F),
    query(g ~= 0.1, g2 ~= 0.1, D, [samples(50)]),
    close_to(D, 3.98942280401433, 1.0e-6).

test(rejection_on_test_evidence) :-
    example(church, F), ddc_load(F),
    query((d ~= D, D >= 2), a ~= 1, P, [samples(6000), seed(13), stderr(SE)]),
    close_to(P, 0.678571, 5*SE).

test(val_evidence_propagates_with_jacobian) :-
    example(indian_gpa, F), ddc_load(F),
    query(student_gpa ~= 3.0, nation ~= a, P, [samples(4000), seed(14), stderr(SE)]),
    A is 0.25*0.95*72*0.75^7*0.25/4, I is 0.75*0.99*630*0.3^4*0.7^4/10,
    close_to(P, A/(A+I), 5*SE).

test(point_mass_beats_density) :-
    example(indian_gpa, F), ddc_load(F),
    query(student_gpa ~= 4, nation ~= a, P, [samples(3000), seed(15)]),
    close_to(P, 1.0, 1.0e-9).

:- end_tests(ddc_evidence).

:- begin_tests(ddc_errors).

test(syntax_error_names_line) :-
    program(['a ~ val(1).', 'b ~ val(2) := a ~= 1', 'c ~ val(3).'], F),
    error_at(ddc_load(F), syntax_error(_), L), memberchk(L, [2, 3]).

test(unknown_distribution) :-
    program(['a ~ val(1).', 'b ~ nosuch(1, 2).'], F),
    error_at(ddc_load(F), distribution(_, unknown_distribution), 2).

test(invalid_parameters_at_load) :-
    program(['a ~ gaussian(0, -1).'], F),
    error_at(ddc_load(F), distribution(_, negative_variance), 1),
    program(['', 'a ~ finite([0.5:x, 0.6:y]).'], F2),
    error_at(ddc_load(F2), distribution(_, probabilities_sum(_)), 2).

test(invalid_parameters_at_run_time) :-
    load_text(['a ~ val(1).', 'b ~ gaussian(0, V) := a ~= A, V is -A.'], M),
    error_at(query(true, b ~= _, _, [program(M), samples(5)]), distribution(_, negative_variance), 2).

test(invalid_gamma_shape_at_run_time) :-
    load_text(['a ~ val(1).', 'b ~ gamma(S, 1.0) := a ~= A, S is -A.'], M),
    error_at(query(true, b ~= _, _, [program(M), samples(5)]), distribution(gamma(_, _), _), 2).

test(non_ground_head) :-
    load_text(['a ~ val(1).', 'b(_) ~ val(1) := a ~= _.', 'q := b(_) ~= 1.'], M),
    error_at(query(true, q, _, [program(M), samples(5)]), non_ground_head(_), 2).

test(non_ground_derived_head) :-
    %   covers(O, A) for every A: not range-restricted, an error naming the
    %   clause, in a query and in a filter step that materialises it
    Lines = ['category(h, hand) := true.', 'carrier(hand) := true.',
             'covers(O, A) := category(O, C), carrier(C), A \\== O.',
             'q := covers(h, _).'],
    load_text(Lines, M),
    error_at(query(true, q, _, [program(M), samples(5)]), non_ground_head(covers(h, _)), 3),
    program(['category(h, hand) := true.', 'carrier(hand) := true.',
             'covers(O, A):t+1 := category(O, C), carrier(C), A \\== O.',
             'x:0 ~ val(0).', 'x:t+1 ~ val(1) := covers(h, a):t.',
             'x:t+1 ~ val(2) := \\+ covers(h, a):t.',
             'observation(o):t+1 ~ val(_) := true.'], F),
    filter_new(F, 3, 1, Fi),
    error_at(forall(between(1, 2, _), filter_step(Fi, [observation(o) ~= 1], [], _)),
             non_ground_head(covers(h, _)), 3),
    filter_free(Fi).

test(overlapping_clauses) :-
    load_text(['a ~ finite([0.5:1, 0.5:2]).', 'b ~ val(1) := a ~= 1.', 'b ~ val(2) := a ~= _.'], M),
    error_at(query(true, b ~= _, _, [program(M), samples(50), seed(1)]), overlapping_clauses(b, _:3), 2).

test(first_applicable_declares_a_decision_list) :-
    load_text([':- first_applicable(b/0).', 'a ~ finite([0.5:1, 0.5:2]).',
               'b ~ val(1) := a ~= 1.', 'b ~ val(2) := a ~= _.'], M),
    query(b ~= 2, P, [program(M), samples(2000), seed(16), stderr(SE)]),
    close_to(P, 0.5, 5*SE).

test(zero_evidence) :-
    load_text(['a ~ finite([0.5:1, 0.5:2]).'], M),
    error_at(query(a ~= 3, a ~= 1, _, [program(M), samples(20)]), zero_evidence(_), _).

test(bad_reload_keeps_previous_program) :-
    program(['a ~ finite([0.25:1, 0.75:2]).'], F),
    ddc_load(F, M),
    program(['a ~ finite([0.25:1, 0.75:2]).', 'b ~ val(1) :- oops('], Bad),
    copy_file(Bad, F),
    error_at(ddc_load(F, M), syntax_error(_), _),
    query(a ~= 1, P, [program(M), samples(5)]),
    close_to(P, 0.25, 1.0e-9).

test(reload_replaces_program) :-
    program(['a ~ finite([0.25:1, 0.75:2]).'], F),
    ddc_load(F, M),
    program(['a ~ finite([0.5:1, 0.5:2]).'], F2),
    copy_file(F2, F),
    ddc_load(F, M),
    query(a ~= 1, P, [program(M), samples(5)]),
    close_to(P, 0.5, 1.0e-9).

test(programs_side_by_side) :-
    load_text(['a ~ finite([0.25:1, 0.75:2]).'], M1),
    load_text(['a ~ finite([0.5:1, 0.5:2]).'], M2),
    M1 \== M2,
    query(a ~= 1, P1, [program(M1), samples(5)]),
    query(a ~= 1, P2, [program(M2), samples(5)]),
    close_to(P1, 0.25, 1.0e-9),
    close_to(P2, 0.5, 1.0e-9).

:- end_tests(ddc_errors).

:- begin_tests(ddc_filter).

pit_world(File) :-
    program([ 'maze(0,0):t ~ val(free).',
              'maze(X,Y):t ~ val(wall) := ( X < 0 ; Y < 0 ).',
              'maze(X,Y):t ~ finite([0.8:free, 0.2:pit]) := X >= 0, Y >= 0, \\+ (X =:= 0, Y =:= 0).',
              ':- persistent(maze/2).',
              'position:0 ~ val((0,0)).',
              'position:t+1 ~ val(P) := position:t ~= (X,Y), action(A), move(A, X, Y, X1, Y1), ( maze(X1,Y1):t ~= wall -> P = (X,Y) ; P = (X1,Y1) ).',
              'move(null, X, Y, X, Y).', 'move(up, X, Y, X, Y1) :- Y1 is Y+1.',
              'move(down, X, Y, X, Y1) :- Y1 is Y-1.', 'move(right, X, Y, X1, Y) :- X1 is X+1.',
              'breeze:t+1 ~ val(B) := position:t+1 ~= (X,Y), ( member((DX,DY), [(0,1),(1,0),(0,-1),(-1,0)]), X1 is X+DX, Y1 is Y+DY, maze(X1,Y1):t+1 ~= pit -> B = true ; B = false ).',
              'observation(breeze):t+1 ~ val(B) := breeze:t+1 ~= B.' ], File).

add_logs(L0, L1, L) :- maplist([X, Y, S]>>(( X =:= -inf ; Y =:= -inf ) -> S = -inf ; S is X + Y), L0, L1, L).

weighted(Flags, LWs, P) :-
    foldl([F, L, S0-Z0, S-Z]>>(( L =:= -inf -> W = 0.0 ; W is exp(L) ), S is S0 + F*W, Z is Z0 + W),
          Flags, LWs, 0.0-0.0, S-Z),
    P is S / Z.

test(pit_world_four_steps) :-
    pit_world(F),
    N = 3000,
    filter_new(F, N, 5, Fi),
    length(Z, N), maplist(=(0.0), Z),
    foldl([A-B, L0, L]>>( filter_step(Fi, [observation(breeze) ~= B], [action(A)], LW), add_logs(L0, LW, L) ),
          [null-false, up-true, down-false, right-true], Z, LWs),
    filter_time(Fi, 4),
    filter_holds(Fi, maze(1,1) ~= free, F11), weighted(F11, LWs, P11),
    close_to(P11, 0.137931, 0.05),
    filter_holds(Fi, maze(2,0):t ~= free, F20), weighted(F20, LWs, P20),
    close_to(P20, 0.689655, 0.07),
    filter_holds(Fi, (maze(0,2) ~= free, maze(1,1) ~= pit, maze(2,0) ~= free), FJ), weighted(FJ, LWs, PJ),
    close_to(PJ, 0.551724, 0.07),
    filter_free(Fi).

%   The filter API calls one engine interface (ddc_filter.pl's header):
%   both engines implement all of it.
test(both_engines_implement_the_engine_interface) :-
    forall(( member(M, [ddc_particles, ddc_filter_batched]),
             member(N/A, [ engine_step/4, engine_undo/1, engine_resample/2, engine_rename/3,
                           engine_holds/3, engine_values/4, engine_rows/5, engine_time/2,
                           engine_size/2, engine_statistics/2, engine_free/1 ]) ),
           ( functor(H, N, A), assertion(predicate_property(M:H, defined)) )).

%   Compiled program clauses call the world runtime by its module, and read
%   a world's time by the position its record declares.
test(compiled_clauses_call_the_world_runtime) :-
    load_text(['a ~ val(1).', 'b ~ val(X) := a ~= Y, X is Y+1.', 'c := b ~= 2.'], M),
    forall(( member(H, [M:'$rv'(_, _, _, _, _, _, _, _, _), M:'$d:c'(_)]), clause(H, B) ),
           \+ ( sub_term(G, B), compound(G), G = ddc:_ )),
    once(( clause(M:'$rv'(b, _, _, _, _, _, _, _, _), B2),
           sub_term(R, B2), subsumes_term(ddc_world:read_key(a, u, _, _), R) )),
    ddc_world:world_time_goal(w, T, G3), G3 = arg(I, w, T),
    ddc_world:world_fields(Fields), nth1(I, Fields, time).

test(undo_resample_values) :-
    pit_world(F),
    filter_new(F, 4, 1, Fi),
    filter_step(Fi, [observation(breeze) ~= false], [action(up)], LW),
    length(LW, 4),
    filter_time(Fi, 1),
    filter_values(Fi, P, position ~= P, Ps), Ps = [(0,1)|_],
    filter_undo(Fi),
    filter_time(Fi, 0),
    filter_values(Fi, P0, position ~= P0, Ps0), maplist(==((0,0)), Ps0),
    filter_values(Fi, X, maze(9,9) ~= X, Mz),
    filter_resample(Fi, [2, 2, 2, 2]),
    filter_values(Fi, X2, maze(9,9) ~= X2, Mz2),
    nth0(2, Mz, V), maplist(==(V), Mz2),
    filter_values(Fi, nope, fail, None), maplist(==(none), None),
    filter_free(Fi).

test(resampled_copies_are_independent_worlds) :-
    %   four copies of one particle: a variable that none of them holds yet
    %   is then sampled in each on its own (a copy shares nothing with the
    %   others), while what they held before is the same in all
    pit_world(F),
    filter_new(F, 4, 3, Fi),
    filter_values(Fi, X, maze(5,5) ~= X, Held),
    filter_resample(Fi, [1, 1, 1, 1]),
    filter_values(Fi, X1, maze(5,5) ~= X1, Held1),
    nth0(1, Held, H), maplist(==(H), Held1),
    findall(Vs, ( between(6, 25, K),
                  filter_values(Fi, Y, maze(K,K) ~= Y, Vs) ), Draws),
    %   20 fresh cells in 4 copies: with P(pit) = 0.2 the copies agree on
    %   all 20 with probability (0.8^4 + 0.2^4)^20, about 1e-7
    \+ maplist([Vs]>>( Vs = [V|Rest], maplist(==(V), Rest) ), Draws),
    filter_free(Fi).

test(observation_without_clause_is_an_error) :-
    pit_world(F),
    filter_new(F, 3, 1, Fi),
    catch(filter_step(Fi, [observation(smell) ~= true], [action(null)], _), error(ddc(no_observation_clause(O), _), _), true),
    O == (observation(smell) ~= true),
    filter_time(Fi, 0),
    filter_free(Fi).

test(filter_is_deterministic) :-
    pit_world(F),
    filter_new(F, 50, 9, A), filter_new(F, 50, 9, B),
    filter_step(A, [observation(breeze) ~= false], [action(up)], LA),
    filter_step(B, [observation(breeze) ~= false], [action(up)], LB),
    LA == LB,
    filter_values(A, X, maze(1,1) ~= X, VA), filter_values(B, X, maze(1,1) ~= X, VB),
    VA == VB,
    filter_free(A), filter_free(B).

test(gaussian_observation_weights) :-
    program([ 'x:0 ~ gaussian(0.0, 1.0).', 'x:t+1 ~ gaussian(X, 0.5) := x:t ~= X.',
              'obs:t+1 ~ gaussian(X, 0.25) := x:t+1 ~= X.' ], F),
    filter_new(F, 5, 3, Fi),
    filter_step(Fi, [obs ~= 0.3], [], LW),
    filter_values(Fi, X, x ~= X, Xs),
    maplist([L, V]>>( E is -0.5*log(2*pi*0.25) - (0.3-V)**2/(2*0.25), abs(E - L) < 1.0e-9 ), LW, Xs),
    filter_free(Fi).

test(uniform_over_a_list_built_in_the_head) :-
    %   the support [behind | Os] is built in the head from a findall_forward
    %   over a timed derived atom (the theory of occlusion's pick_occluder):
    %   each particle picks one of the three once a vanishes, and keeps it
    program([ 'pos(A):t+1 ~ val(P) := observed(A), observation(pos(A)) ~= P.',
              'pos(A):t+1 ~ val(P) := object(A), \\+ observed(A), pos(A):t ~= P.',
              'seen(A):t+1 := observed(A).',
              'hidden(A):t+1 := object(A), \\+ observed(A).',
              'cand(A, O):t+1 := hidden(A):t+1, observed(O), O \\== A, pos(O):t+1 ~= _.',
              'pick(A):t+1 ~ uniform([behind | Os]) := hidden(A):t+1, seen(A):t, findall_forward(O, cand(A, O):t+1, Os0), sort(Os0, Os), Os \\== [].',
              'under(A, O):t+1 := pick(A):t+1 ~= O, O \\== behind.',
              'under(A, O):t+1 := under(A, O):t, hidden(A):t+1.',
              'observation(pos(A)):t+1 ~ val(_) := object(A).' ], F),
    filter_new(F, 30, 1, Fi),
    Objects = [object(a), object(b), object(c)],
    Step = [Seen]>>( findall(X, ( member(O, Seen), ( X = observed(O) ; X = (observation(pos(O)) ~= 1.0) ) ), Obs),
                     filter_step(Fi, Obs, Objects, _) ),
    maplist(Step, [[a, b, c], [a, b, c], [b, c]]),
    filter_values(Fi, U3, under(a, U3), Us3),
    maplist(Step, [[b, c], [b, c]]),
    filter_values(Fi, U5, under(a, U5), Us5),
    Us5 == Us3,
    %   30 particles over three choices: each is missed with probability (2/3)^30
    msort(Us5, Sorted), sort(Sorted, Kinds), Kinds == [b, c, none],
    filter_free(Fi).

%   filter_rows/6: a variable's values as rows of floats, read from the
%   stores (x:t ~= V) or proved (the same read in a conjunction), NaN rows
%   where it is undefined (x exists only where c is a); tuples give wider
%   rows; atoms give no rows but the values.
test(rows_of_floats) :-
    program([ 'c:0 ~ uniform([a, b]).', 'c:t+1 ~ val(C) := c:t ~= C.',
              'x:t+1 ~ gaussian(0.0, 1.0) := c:t+1 ~= a.',
              'p:t+1 ~ val((X, 2)) := x:t+1 ~= X.' ], F),
    filter_new(F, 40, 3, [engine(per_particle)], Fi),      % (reads its stores below)
    filter_step(Fi, [], [], _),
    filter_rows(Fi, X, x:t ~= X, 1, Stored, []),
    filter_rows(Fi, X1, (x:t ~= X1, true), 1, Proved, []),
    Stored == Proved, length(Stored, 40),
    ddc_filter:filter_state(Fi, St), ddc_particles:particles_size(St, N),
    ddc_particles:particles_time(St, T), ddc_particles:particles_worlds(St, Ws),
    ddc_particles:particles_shared(St, Sh), ddc_world:shared_store(Sh, SS),
    ddc_particles:stored_rows(1, N, Ws, SS, x-T, 1, Stored),     % (read from the stores)
    filter_values(Fi, C, c:t ~= C, Cs),
    maplist([Ci, Xi]>>( Ci == a -> Xi =:= Xi ; Xi =\= Xi ), Cs, Stored),
    memberchk(a, Cs), memberchk(b, Cs),
    filter_rows(Fi, P, p:t ~= P, 2, Pairs, []), length(Pairs, 80),
    filter_rows(Fi, C1, c:t ~= C1, W, Fl, Vs), W == 0, Fl == [],
    maplist([Ci, value(Ci)]>>true, Cs, Vs),
    filter_free(Fi).

:- end_tests(ddc_filter).
