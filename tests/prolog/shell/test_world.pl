:- use_module('../../../prolog/shell/world').
:- use_module(library(plunit)).

world_file(File) :-
    tmp_file_stream(text, File, S),
    format(S, ":- dynamic anchor/5, attribute/3, particle/2, particle_fact/2.~n", []),
    format(S, "anchor(ball_1, 'ball-1', ball, false, 3.2).~n", []),
    format(S, "anchor(mug_1, 'mug-1', mug, true, 5.0).~n", []),
    format(S, "attribute(ball_1, position, (0.1, 0.0, 0.03)).~n", []),
    forall(between(0, 3, I),
           ( format(S, "particle(~d, 0.25).~n", [I]),
             X is 0.1 * I,
             format(S, "particle_fact(~d, pos(ball_1, (~w, 0.0, 0.03))).~n", [I, X]) )),
    format(S, "particle_fact(0, occluded_by(ball_1, mug_1)).~n", []),
    format(S, "particle_fact(1, occluded_by(ball_1, mug_1)).~n", []),
    format(S, "particle_fact(2, occluded_by(ball_1, box_1)).~n", []),
    close(S).

:- begin_tests(world).

test(anchors, As == [ball_1, mug_1]) :-
    world_file(F), load_world(F), anchors(As).

test(prob_of_an_occluder, P =:= 0.5) :-
    world_file(F), load_world(F), prob(occluded_by(ball_1, mug_1), P).

test(prob_with_a_test, P =:= 0.5) :-
    world_file(F), load_world(F), prob((pos(ball_1, (X, _, _)), X > 0.15), P).

test(occluders_most_probable_first, D == [0.5-mug_1, 0.25-box_1]) :-
    world_file(F), load_world(F), occluders(ball_1, D).

test(where, [true(abs(X-0.15) < 1e-9)]) :-
    world_file(F), load_world(F), where(ball_1, (X, _, _), Spread),
    assertion(abs(Spread - sqrt(0.0125)) < 1e-9).

test(reload_replaces, As == [ball_1, mug_1]) :-
    world_file(F), load_world(F), load_world(F), anchors(As).

:- end_tests(world).
