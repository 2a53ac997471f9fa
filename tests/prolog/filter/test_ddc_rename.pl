/*  plunit tests of filter_rename/3 (prolog/ddc/filter/ddc_filter.pl): constants
    renamed inside chosen particles, in both engines.  Probabilistic checks
    use fixed seeds and tolerances of 5 standard errors.
*/
:- use_module('../../../prolog/ddc').
:- use_module(library(plunit)).
:- use_module(library(lists)).
:- use_module(library(apply)).
:- use_module(library(yall)).

%   program(+Lines, -File): a DDC program in a temporary file.
program(Lines, File) :-
    tmp_file_stream(text, File, S),
    forall(member(L, Lines), format(S, "~w~n", [L])),
    close(S).

%   Two mugs and a ball hidden under one of them (mug_1 with probability
%   0.8).  A mug moves where an action says, else stays; the ball keeps
%   its mug (read one step back through a derived atom, which the engines
%   materialise) and is where its mug is.
mugs(File) :-
    program([ ':- dynamic(move/2).',
              'mug(mug_1) := true.',
              'mug(mug_2) := true.',
              'ball(ball_1) := true.',
              'start(mug_1, 0.0) := true.',
              'start(mug_2, 1.0) := true.',
              'pos(M):0 ~ val(X) := mug(M), start(M, X).',
              'hidden_under(B):0 ~ finite([0.8:mug_1, 0.2:mug_2]) := ball(B).',
              'pos(B):0 ~ val(X) := ball(B), hidden_under(B):0 ~= M, pos(M):0 ~= X.',
              'under(B, M):t := hidden_under(B):t ~= M.',
              'pos(M):t+1 ~ val(X) := mug(M), move(M, X).',
              'pos(M):t+1 ~ val(X) := mug(M), \\+ move(M, _), pos(M):t ~= X.',
              'hidden_under(B):t+1 ~ val(M) := ball(B), under(B, M):t.',
              'pos(B):t+1 ~ val(X) := ball(B), hidden_under(B):t+1 ~= M, pos(M):t+1 ~= X.',
              'observation(pos(M)):t+1 ~ gaussian(X, 0.01) := pos(M):t+1 ~= X.'
            ], File).

swap([mug_1-mug_2, mug_2-mug_1]).

%   state(+F, -Vs): per particle, what it holds of the ball and the mugs
%   at t and t-1 (none for a time it no longer holds).
state(F, Vs) :-
    filter_values(F, s(H, P, M1, M2, U, Before),
                  ( hidden_under(ball_1):t ~= H, pos(ball_1):t ~= P,
                    pos(mug_1):t ~= M1, pos(mug_2):t ~= M2, under(ball_1, U):t,
                    (   hidden_under(ball_1):t-1 ~= H0, pos(mug_1):t-1 ~= A0,
                        pos(mug_2):t-1 ~= B0
                    ->  Before = (H0, A0, B0)
                    ;   Before = none
                    ) ),
                  Vs).

digest(F, D) :-
    state(F, Vs),
    variant_sha1(Vs, D).

%   renamed(+S0, -S): what a particle holding S0 holds once mug_1 and
%   mug_2 swap names.
renamed(s(H, P, M1, M2, U, Before), s(H1, P, M2, M1, U1, Before1)) :-
    other(H, H1), other(U, U1),
    (   Before = (H0, A0, B0) -> other(H0, H01), Before1 = (H01, B0, A0) ; Before1 = none ).

other(mug_1, mug_2).
other(mug_2, mug_1).

new_filter(Engine, N, Seed, Threads, F) :-
    mugs(File),
    filter_new(File, N, Seed, [engine(Engine), threads(Threads)], F),
    filter_engine(F, Engine).

engine(per_particle).
engine(batched).

:- begin_tests(ddc_rename).

%   After a rename in half the particles (with repeats), those hold the
%   renamed values (also of t-1 and the materialised derived atom), the
%   others theirs.
test(renamed_values_in_exactly_those_particles, [forall(engine(E))]) :-
    new_filter(E, 8, 3, 1, F),
    filter_step(F, [], [], _),
    state(F, Vs0),
    swap(R),
    filter_rename(F, R, [1, 3, 3, 5, 7, 1]),
    state(F, Vs1),
    forall(nth1(I, Vs0, S0),
           (   nth1(I, Vs1, S1),
               (   I mod 2 =:= 1 -> renamed(S0, S) ; S = S0 ),
               assertion(S1 == S)
           )),
    filter_free(F).

%   A rename at time 0 (no step yet, no t-1) renames the prior's values.
test(rename_at_time_zero, [forall(engine(E))]) :-
    new_filter(E, 6, 4, 1, F),
    state(F, Vs0),
    swap(R),
    filter_rename(F, R, all),
    state(F, Vs1),
    maplist(renamed, Vs0, Vs),
    assertion(Vs1 == Vs),
    filter_free(F).

%   The next step goes on from the renamed worlds: the ball keeps the mug
%   it is under by its new name, and follows that mug (mug_1 moves to 5.0,
%   mug_2 stays where it is).
test(hidden_ball_follows_the_renamed_mug, [forall(( engine(E), member(K, [1, 2]) ))]) :-
    new_filter(E, 10, 5, K, F),
    filter_step(F, [], [], _),
    state(F, Vs0),
    swap(R),
    filter_rename(F, R, [1, 3, 5, 7, 9]),           % (in both groups of threads(2))
    filter_step(F, [], [move(mug_1, 5.0)], _),
    state(F, Vs1),
    forall(nth1(I, Vs0, s(H0, P0, A0, B0, _, _)),
           (   nth1(I, Vs1, s(H1, P1, M1, M2, U1, Before)),
               (   I mod 2 =:= 1 -> other(H0, H) ; H = H0 ),
               assertion(H1 == H), assertion(U1 == H),
               assertion(M1 == 5.0),
               (   I mod 2 =:= 1 -> assertion(M2 == A0) ; assertion(M2 == B0) ),
               (   H == mug_1 -> assertion(P1 == 5.0) ; assertion(P1 == P0) ),
               assertion(Before = (H, _, _))
           )),
    filter_free(F).

%   A rename after a resampling renames the resampled particles, t-1
%   included (the batched engine resamples t-1 when first read).
test(rename_after_resampling, [forall(( engine(E), member(K, [1, 2]) ))]) :-
    new_filter(E, 6, 14, K, F),
    filter_step(F, [], [], _),
    state(F, Vs0),
    Is = [5, 5, 0, 2, 3, 3],
    filter_resample(F, Is),
    swap(R),
    filter_rename(F, R, [2, 3, 6]),
    state(F, Vs1),
    forall(nth1(I, Is, J0),
           (   J is J0+1, nth1(J, Vs0, S0), nth1(I, Vs1, S1),
               (   memberchk(I, [2, 3, 6]) -> renamed(S0, S) ; S = S0 ),
               assertion(S1 == S)
           )),
    filter_free(F).

%   An observation weighs the renamed worlds: mug_1 seen at 1.0 (where
%   mug_2 was) is likely only in the renamed particles.
test(observation_weighs_the_renamed_worlds, [forall(engine(E))]) :-
    new_filter(E, 6, 6, 1, F),
    swap(R),
    filter_rename(F, R, [2, 4, 6]),
    filter_step(F, [observation(pos(mug_1)) ~= 1.0], [], LWs),
    forall(nth1(I, LWs, LW),
           (   I mod 2 =:= 0 -> assertion(LW > 0) ; assertion(LW < -40) )),
    filter_free(F).

%   Both engines give the same distribution after a rename in the first
%   half of the particles: there the ball is under mug_1 (which moves)
%   with probability 0.2, in the second half 0.8.
test(engines_agree_in_distribution) :-
    N = 2000, Half is N // 2,
    swap(R),
    numlist(1, Half, First),
    findall(E-(P1, P2),
            ( engine(E),
              new_filter(E, N, 7, 1, F),
              filter_rename(F, R, First),
              filter_step(F, [], [move(mug_1, 5.0)], _),
              filter_holds(F, pos(ball_1):t ~= 5.0, Flags),
              length(Fl1, Half), append(Fl1, Fl2, Flags),
              sum_list(Fl1, S1), sum_list(Fl2, S2),
              P1 is S1/Half, P2 is S2/Half,
              filter_free(F) ),
            [per_particle-(A1, A2), batched-(B1, B2)]),
    Tol is 5*sqrt(0.2*0.8/Half),
    assertion(abs(A1 - 0.2) =< Tol), assertion(abs(A2 - 0.8) =< Tol),
    assertion(abs(B1 - 0.2) =< Tol), assertion(abs(B2 - 0.8) =< Tol),
    assertion(abs(A1 - B1) =< sqrt(2)*Tol), assertion(abs(A2 - B2) =< sqrt(2)*Tol).

%   A renaming of identity pairs, or of constants no particle holds,
%   changes nothing: the same values, and the same particles after the
%   next steps as a filter that was not renamed.
test(identity_rename_changes_nothing, [forall(engine(E))]) :-
    Steps = [[]-[], [observation(pos(mug_2)) ~= 1.0]-[move(mug_1, 2.0)]],
    findall(Trace,
            ( member(R, [none, [mug_1-mug_1, mug_2-mug_2], [cup_a-cup_b, cup_b-cup_a]]),
              new_filter(E, 12, 8, 2, F),
              filter_step(F, [], [], _),
              digest(F, D0),
              ( R == none -> true ; filter_rename(F, R, [2, 5, 11]) ),
              digest(F, D1),
              assertion(D1 == D0),
              findall(LW-D, ( member(O-A, Steps), filter_step(F, O, A, LW), digest(F, D) ),
                      Trace),
              filter_free(F) ),
            [T0|Ts]),
    forall(member(T, Ts), assertion(T == T0)).

%   filter_undo/1 after a rename and a step undoes the step and keeps the
%   rename; after a rename alone it goes back to before the last step.
test(undo_keeps_the_rename, [forall(engine(E))]) :-
    new_filter(E, 8, 9, 1, F),
    filter_step(F, [], [], _),
    digest(F, Stepped),
    swap(R),
    filter_rename(F, R, [1, 2]),
    digest(F, Renamed),
    assertion(Renamed \== Stepped),
    filter_step(F, [], [move(mug_2, 3.0)], _),
    filter_undo(F),
    digest(F, Undone),
    assertion(Undone == Renamed),
    filter_step(F, [], [move(mug_2, 3.0)], _),
    filter_rename(F, R, [3]),
    filter_undo(F),
    filter_time(F, 1),
    digest(F, Before),
    assertion(Before == Renamed),
    filter_free(F).

%   A bad renaming or particle list is an ISO error with the predicate as
%   context, and the filter is unchanged.
test(errors, [forall(engine(E))]) :-
    new_filter(E, 6, 10, 1, F),
    filter_step(F, [], [], _),
    digest(F, D0),
    forall(member(R-Ps-Formal,
                  [ foo-all-type_error(list, foo),
                    [mug_1]-all-type_error(pair, mug_1),
                    [mug_1-3]-all-type_error(atom, 3),
                    [mug_1-mug_2]-all-domain_error(permutation, [mug_1-mug_2]),
                    [mug_1-mug_2, mug_2-mug_1, mug_1-mug_1]-all-domain_error(permutation, _),
                    [mug_1-mug_2, mug_2-mug_3]-all-domain_error(permutation, _),
                    [mug_1-mug_2, mug_2-mug_1]-[0]-domain_error(between(1, 6), 0),
                    [mug_1-mug_2, mug_2-mug_1]-[1, 7]-domain_error(between(1, 6), 7),
                    [mug_1-mug_2, mug_2-mug_1]-[a]-type_error(integer, a),
                    [mug_1-mug_2, mug_2-mug_1]-some-type_error(list, some)
                  ]),
           (   catch(( filter_rename(F, R, Ps), Caught = none ), Err, Caught = Err),
               assertion(subsumes_term(error(Formal, context(filter_rename/3, _)), Caught))
           )),
    digest(F, D1),
    assertion(D1 == D0),
    filter_free(F).

%   An untimed value (per-particle engine: untimed random variables are
%   outside the batched fragment) is renamed too, key and value.
test(untimed_values_renamed) :-
    program([ 'favourite ~ finite([0.5:mug_1, 0.5:mug_2]).',
              'colour(mug_1) ~ val(red).',
              'colour(mug_2) ~ val(blue).',
              'x:0 ~ val(0).',
              'x:t+1 ~ val(Y) := x:t ~= X, Y is X+1.' ], File),
    filter_new(File, 6, 11, F),
    filter_engine(F, per_particle),
    filter_values(F, Fav-C1-C2, ( favourite ~= Fav, colour(mug_1) ~= C1, colour(mug_2) ~= C2 ),
                  Vs0),
    swap(R),
    filter_rename(F, R, [1, 2, 3]),
    filter_step(F, [], [], _),
    filter_values(F, Fav-C1-C2, ( favourite ~= Fav, colour(mug_1) ~= C1, colour(mug_2) ~= C2 ),
                  Vs1),
    forall(nth1(I, Vs0, Fav0-red-blue),
           (   nth1(I, Vs1, V1),
               (   I =< 3 -> other(Fav0, Fav1), V = Fav1-blue-red ; V = Fav0-red-blue ),
               assertion(V1 == V)
           )),
    filter_free(F).

:- end_tests(ddc_rename).

%   The per-particle engine's shared values: a value held once for all
%   particles that a rename changes becomes each particle's own, so that
%   the particles stay bit for bit those of computing everything in every
%   particle (share(false)).  The program of test_ddc_shared.pl's kind: a
%   box and a ball, the ball hidden under the box in some frames, the
%   observations read untimed, values shared, then held per particle,
%   then shared again; box and ball swap names in some particles
%   mid-run.
shared_program(File) :-
    program([ ':- first_applicable(pos/1).',
              ':- first_applicable(observation/1).',
              'pos(A):t+1 ~ val(P) := observed(A), observation(pos(A)) ~= P, \\+ pos(A):t ~= _.',
              'pos(A):t+1 ~ val(M) := observed(A), observation(pos(A)) ~= O, pos(A):t ~= X, seen(A):t, M is X + 0.5*(O-X).',
              'pos(A):t+1 ~ val(O) := observed(A), observation(pos(A)) ~= O.',
              'pos(A):t+1 ~ gaussian(M, 0.01) := hidden(A):t+1, under(A, B):t+1, pos(B):t+1 ~= M.',
              'pos(A):t+1 ~ gaussian(X, 0.04) := hidden(A):t+1, pos(A):t ~= X.',
              'seen(A):t+1 := observed(A).',
              'hidden(A):t+1 := object(A), \\+ observed(A).',
              'pick(A):t+1 ~ uniform([B, none]) := hidden(A):t+1, seen(A):t, object(B), B \\== A, observed(B).',
              'under(A, B):t+1 := hidden(A):t+1, pick(A):t+1 ~= B, B \\== none.',
              'under(A, B):t+1 := under(A, B):t, hidden(A):t+1.',
              'observation(pos(A)):t+1 ~ gaussian(X, 0.05) := pos(A):t ~= X.',
              'observation(pos(A)):t+1 ~ val(_) := object(A), \\+ pos(A):t ~= _.'
            ], File).

shared_frames([ [box-1.0, ball-1.2], [box-1.1, ball-1.3], [box-1.2], [box-1.4], [box-1.5],
                [box-1.6, ball-1.65], [box-1.7, ball-1.72], [box-1.8, ball-1.81] ]).

%   shared_run(+Options, -Trace): log weights and values after every step;
%   box and ball swap names in every third particle after steps 2 and 6,
%   in particles 1-10 after step 4.
shared_run(Options, Trace) :-
    shared_program(File),
    filter_new(File, 30, 12, [engine(per_particle)|Options], F),
    shared_frames(Frames),
    findall(LW-Vs,
            ( nth1(K, Frames, Seen),
              findall(X, ( member(O-P, Seen),
                           ( X = observed(O) ; X = (observation(pos(O)) ~= P) ) ), Obs),
              filter_step(F, Obs, [object(box), object(ball)], LW),
              (   memberchk(K, [2, 6])
              ->  numlist(1, 30, All), include([I]>>(I mod 3 =:= 0), All, Is),
                  filter_rename(F, [box-ball, ball-box], Is)
              ;   K == 4
              ->  numlist(1, 10, Is),
                  filter_rename(F, [box-ball, ball-box], Is)
              ;   true
              ),
              filter_values(F, P-Q-U, ( pos(ball):t ~= P, pos(box):t ~= Q,
                                        ( under(ball, U):t -> true ; U = none ) ), Vs) ),
            Trace),
    filter_free(F).

:- begin_tests(ddc_rename_shared).

test(renamed_shared_values_are_those_of_unshared_particles, [forall(member(K, [1, 2]))]) :-
    shared_run([share(true), threads(K)], Shared),
    shared_run([share(false), threads(K)], Unshared),
    assertion(Shared == Unshared).

%   The renamed particles hold box's values under ball and ball's under
%   box: right after a rename of all particles, every particle's two
%   positions are swapped.
test(rename_swaps_shared_values) :-
    shared_program(File),
    filter_new(File, 10, 13, [engine(per_particle)], F),
    filter_step(F, [observed(box), observation(pos(box)) ~= 1.0, observed(ball),
                    observation(pos(ball)) ~= 2.0], [object(box), object(ball)], _),
    filter_statistics(F, Stats0), memberchk(shared(S0), Stats0),
    assertion(S0 > 0),
    filter_values(F, P-Q, ( pos(ball):t ~= P, pos(box):t ~= Q ), Vs0),
    assertion(maplist(==(2.0-1.0), Vs0)),
    filter_rename(F, [box-ball, ball-box], all),
    filter_values(F, P-Q, ( pos(ball):t ~= P, pos(box):t ~= Q ), Vs1),
    assertion(maplist(==(1.0-2.0), Vs1)),
    filter_free(F).

:- end_tests(ddc_rename_shared).
