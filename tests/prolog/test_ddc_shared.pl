/*  plunit tests of shared values in the particle filter (prolog/ddc.pl,
    "Shared values"): a value computed only from observations, facts and
    other shared values is computed once for all particles; the particles
    are bit for bit those of computing everything in every particle.
    (Shared values and this file's threads are the per-particle engine's:
    every filter here is made with engine(per_particle).)
*/
:- use_module('../../prolog/ddc').
:- use_module(library(plunit)).
:- use_module(library(lists)).
:- use_module(library(apply)).

%   A perceived box (its position the filtered observation: shared) and a
%   ball that is hidden under the box in some frames (its position sampled:
%   the particles' own) and is then seen again where it is perceived
%   (shared again once every particle agrees).
program(File) :-
    tmp_file_stream(text, File, S),
    forall(member(L,
        [ ':- first_applicable(pos/1).',
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
        ]),
        format(S, "~w~n", [L])),
    close(S).

frames([ [box-1.0, ball-1.2], [box-1.1, ball-1.3], [box-1.2], [box-1.4], [box-1.5],
         [box-1.6, ball-1.65], [box-1.7, ball-1.72], [box-1.8, ball-1.81] ]).

step(F, Seen) :-
    findall(X, ( member(O-P, Seen), ( X = observed(O) ; X = (observation(pos(O)) ~= P) ) ), Obs),
    filter_step(F, Obs, [object(box), object(ball)], LW),
    nb_setval(test_ddc_shared_lw, LW).

%   run(+Options, -Trace): log weights and particle values after every step,
%   resampling (a fixed, uneven choice) after every other one.
run(Options, Trace) :-
    program(File),
    filter_new(File, 40, 11, [engine(per_particle)|Options], F),
    frames(Frames),
    findall(LW-Vs, ( nth1(K, Frames, Seen),
                     step(F, Seen), nb_getval(test_ddc_shared_lw, LW),
                     filter_values(F, P-U, ( pos(ball):t ~= P, ( under(ball, U):t -> true ; U = none ) ), Vs),
                     (   K mod 2 =:= 0
                     ->  numlist(1, 40, Is0), maplist([I, J]>>(J is (I*7) mod 13), Is0, Is),
                         filter_resample(F, Is)
                     ;   true
                     ) ),
            Trace),
    filter_free(F).

own_entries(F, O) :-
    filter_statistics(F, Stats),
    memberchk(own(O), Stats).

:- begin_tests(ddc_shared).

test(sharing_changes_no_particle) :-
    run([share(true)], Shared),
    run([share(false)], Unshared),
    Shared == Unshared,
    %   and the run did something: while hidden, the ball was believed under
    %   the box in some particles and not in others
    nth1(4, Shared, _-Vs), memberchk(_-box, Vs), memberchk(_-none, Vs).

test(a_frame_the_particles_agree_on_is_computed_once) :-
    program(File),
    filter_new(File, 30, 3, [engine(per_particle), share(true)], F),
    frames([S1, S2, S3|_]),
    step(F, S1), step(F, S2),
    filter_statistics(F, St2), memberchk(settled_steps(K2), St2),
    K2 =:= 2,
    step(F, S3),                    % the ball vanishes: particles disagree
    filter_statistics(F, St3), memberchk(settled_steps(K3), St3),
    K3 =:= 2,
    filter_free(F).

test(perceived_values_are_held_once) :-
    program(File),
    filter_new(File, 30, 3, [engine(per_particle), share(true)], F),
    filter_new(File, 30, 3, [engine(per_particle), share(false)], G),
    frames([S1, S2, S3|_]),
    forall(member(Seen, [S1, S2]), ( step(F, Seen), step(G, Seen) )),
    %   everything is perceived: nothing of a particle's own
    own_entries(F, 0),
    own_entries(G, OG), OG >= 30,
    %   the ball vanishes: its position and pick are the particles' own
    step(F, S3), own_entries(F, OF3), OF3 >= 30,
    filter_free(F), filter_free(G).

test(agreed_values_become_shared) :-
    program(File),
    filter_new(File, 30, 5, [engine(per_particle), share(true)], F),
    frames(Frames), length(Pre, 6), append(Pre, _, Frames),
    maplist(step(F), Pre),          % the ball is seen again in the 6th frame
    filter_values(F, P, pos(ball):t ~= P, Ps),
    sort(Ps, [_]),                  % where it is perceived, in every particle
    filter_statistics(F, Stats), memberchk(shared(S), Stats), S > 0,
    %   the ball's position at t is no particle's own any more: the next
    %   step, everything perceived, leaves nothing in the particles
    frames(All), nth1(7, All, S7), step(F, S7),
    own_entries(F, 0),
    filter_free(F).

test(undo_restores_shared_values) :-
    program(File),
    filter_new(File, 20, 7, [engine(per_particle), share(true)], F),
    frames([S1, S2|_]),
    step(F, S1),
    filter_values(F, P, pos(box):t ~= P, Before),
    filter_statistics(F, St1),
    step(F, S2),
    filter_undo(F),
    filter_statistics(F, St2),
    St1 == St2,
    filter_values(F, P2, pos(box):t ~= P2, After),
    Before == After,
    filter_free(F).

%   Threads: particles 2..N split into groups stepped by threads of their
%   own, each with its own random stream; their particles and shared values
%   are joined back.
test(sharing_changes_no_particle_in_threads) :-
    run([share(true), threads(3)], Shared),
    run([share(false), threads(3)], Unshared),
    Shared == Unshared,
    nth1(4, Shared, _-Vs), memberchk(_-box, Vs), memberchk(_-none, Vs).

test(threads_are_deterministic) :-
    run([threads(2)], A),
    run([threads(2)], B),
    A == B.

test(every_group_steps_its_particles) :-
    run([threads(3)], Trace),
    run([threads(1)], Trace1),
    Trace \== Trace1,              % other random streams
    nth1(4, Trace, LW-Vs),          % the ball hidden: a value in every particle
    length(LW, 40), length(Vs, 40),
    forall(member(P-_, Vs), number(P)),
    %   the groups (2..14, 15..27, 28..40) drew from different streams
    nth1(3, Vs, P3-_), nth1(16, Vs, P16-_), nth1(29, Vs, P29-_),
    P3 =\= P16, P16 =\= P29, P3 =\= P29.

%   An error in a group stops the step and the filter is as before it: the
%   particles, and what they hold of the step before (x:t-1, a random draw,
%   would be drawn anew if a particle had lost it).  The observation has no
%   clause where pick is b; with this seed the first 20 particles (the first
%   and the calling thread's group) all have a, so the error is raised in
%   the other thread's group (particles 21..40).
test(an_error_in_another_thread_changes_nothing) :-
    error_midway_changes_nothing(2).

%   The same error in one thread: particles 1..28 have been stepped (each
%   copied first) when particle 29 raises it.
test(an_error_midway_changes_nothing) :-
    error_midway_changes_nothing(1).

error_midway_changes_nothing(Threads) :-
    tmp_file_stream(text, File, S),
    forall(member(L, [ 'pick:0 ~ finite([0.97:a, 0.03:b]) := true.',
                       'pick:t+1 ~ val(P) := pick:t ~= P.',
                       'x:0 ~ uniform([1, 2, 3, 4, 5, 6, 7, 8, 9]) := true.',
                       'x:t+1 ~ val(X) := x:t ~= X.',
                       'observation(x):t+1 ~ gaussian(0, 1) := pick:t ~= a.' ]),
           format(S, "~w~n", [L])),
    close(S),
    filter_new(File, 40, 3, [engine(per_particle), threads(Threads)], F),
    filter_values(F, P, pick:t ~= P, Picks),
    length(First, 20), append(First, Others, Picks),
    forall(member(X, First), X == a), memberchk(b, Others),
    filter_step(F, [], [], _),
    Query = ( pick:t ~= P1, (x:t-1) ~= X1 ),   % the step before is still readable
    filter_values(F, P1-X1, Query, Before),
    catch(filter_step(F, [observation(x) ~= 0.5], [], _), E, true),
    nonvar(E), E = error(ddc(no_observation_clause(_), _), _),
    filter_time(F, 1),
    filter_values(F, P1-X1, Query, After),
    Before == After,
    filter_step(F, [], [], _),      % and it goes on
    filter_time(F, 2),
    filter_free(F).

test(grouped_shared_values_are_joined) :-
    program(File),
    filter_new(File, 30, 3, [engine(per_particle), threads(2)], F),
    frames([S1, S2, S3|_]),
    step(F, S1), step(F, S2),
    own_entries(F, 0),              % settled: nothing split
    step(F, S3),                    % the ball vanishes: split into groups
    filter_statistics(F, Stats), memberchk(shared(Sh), Stats), Sh > 0,
    own_entries(F, O), O >= 30,
    filter_values(F, P, pos(box):t ~= P, Ps),
    sort(Ps, [_]),                  % the box, shared, the same in every group
    filter_free(F).

%   Joining a group's shared values (ddc_particles:merge_shared/4): new shared values
%   join, new per-particle keys join the impure keys, and a value one side
%   shared while the other held it per particle ends up in every particle of
%   the sharing side instead (a defensive case: with both sides starting from
%   the same shared values it should not arise).
test(joining_a_group_keeps_each_value_where_it_is_read) :-
    maplist(ddc_store:store_new, [Sh1, Im1, Sh2, Im2]),
    ddc_store:store_put(Sh1, a-1, 1.0),          % shared here, per particle there
    ddc_store:store_put(Im1, b-1, true),         % per particle here, shared there
    ddc_store:store_put(Sh2, b-1, 2.0),
    ddc_store:store_put(Im2, a-1, true),
    ddc_store:store_put(Sh2, c-1, 3.0),          % new, shared there
    ddc_store:store_put(Im2, d-1, true),         % new, per particle there
    findall(w(S), ( between(1, 4, _), ddc_store:store_new(S) ), L),
    Ws =.. [ws|L],
    arg(1, Ws, w(S1)), ddc_store:store_put(S1, b-1, 9.0),
    arg(4, Ws, w(S4)), ddc_store:store_put(S4, a-1, 7.0),
    Sh = shared(Sh1, Im1, [], true, 0, 2),
    ddc_particles:merge_shared(Sh, shared(Sh2, Im2, [], true, 0, 2), Ws, 3-2),
    ddc_store:store_get(Sh1, c-1, 3.0),
    \+ ddc_store:store_get(Sh1, a-1, _), ddc_store:store_get(Im1, a-1, _),
    \+ ddc_store:store_get(Sh1, b-1, _),
    ddc_store:store_get(Im1, d-1, _),
    %   a: shared on this side (particles 1, 2), now their own; particle 4
    %   keeps its own value
    findall(V, ( between(1, 4, I), arg(I, Ws, w(S)),
                 ( ddc_store:store_get(S, a-1, V) -> true ; V = none ) ), [1.0, 1.0, none, 7.0]),
    %   b: shared by the group (particles 3, 4), now their own
    findall(V, ( between(1, 4, I), arg(I, Ws, w(S)),
                 ( ddc_store:store_get(S, b-1, V) -> true ; V = none ) ), [9.0, none, 2.0, 2.0]).

%   A query that is a single read `h ~= V` of a ground variable answers from
%   the stores (ddc_particles:stored_read/6, stored_values/8); the answers are those of
%   proving it (the same read in a conjunction goes the general way), for a
%   value of the particle's own, a shared one, one undefined in some
%   particles (pick/1 once the ball is seen), and a key no particle holds
%   yet (pos(cup): proved, which records it as undefined).
test(stored_reads_answer_as_proofs_do) :-
    program(File),
    filter_new(File, 30, 5, [engine(per_particle), threads(2)], F),
    frames(Frames),
    forall(member(Seen, Frames),
           (   step(F, Seen),
               particles_state(F, N, T, Ws, SS, _),
               \+ ddc_particles:stored_values(1, N, Ws, SS, pos(cup)-T, _, _, _),
               forall(member(X, [pos(ball), pos(box), pick(ball), pos(cup)]),
                      (   filter_values(F, v(V), X:t ~= V, Stored),
                          filter_values(F, v(V1), (X:t ~= V1, true), Proved),
                          Stored == Proved
                      ))
           )),
    filter_values(F, v(V2), pos(cup):t ~= V2, Cup), maplist(==(none), Cup),
    filter_values(F, v(V3), pos(ball):t ~= V3, Ball), \+ memberchk(none, Ball),
    %   the stored path did answer for the ball
    particles_state(F, N1, T1, Ws1, SS1, _),
    ddc_particles:stored_values(1, N1, Ws1, SS1, pos(ball)-T1, V4, v(V4), Ball),
    filter_free(F).

%   A particle's own store is not indexed: a read with a partly bound key
%   scans it and finds what an indexed store finds through its index.
test(unindexed_store_finds_what_an_index_finds) :-
    ddc_store:store_new(I, true), ddc_store:store_new(U, false),
    forall(member(K-V, [pos(a)-3-1.0, pos(b)-3-2.0, pos(a)-2-0.5, vel(a)-3-0.1, x-u-7]),
           ( ddc_store:store_put(I, K, V), ddc_store:store_put(U, K, V) )),
    findall(X-V, ddc_store:store_match(I, pos(X)-3, V), FromIndex),
    findall(X-V, ddc_store:store_match(U, pos(X)-3, V), FromScan),
    msort(FromIndex, L), msort(FromScan, L), L == [a-1.0, b-2.0],
    ddc_store:store_size(I, 5), ddc_store:store_size(U, 5),
    \+ ddc_store:store_get(U, '$by'(pos/1, 3), _),
    ddc_store:store_get(I, '$by'(pos/1, 3), _).

%   The sweep plan (ddc_world:plan_sweep/3): after the first particle, the other
%   particles sweep exactly the transition clauses that are some particle's
%   own (their '$swept' marks among the impure keys), and skip the shared
%   ones.
test(the_sweep_plan_lists_the_clauses_particles_sweep_on_their_own) :-
    program(File),
    filter_new(File, 20, 3, [engine(per_particle)], F),
    frames([S1, S2, S3|_]),
    step(F, S1), step(F, S2), step(F, S3),     % the ball vanishes in S3
    particles_state(F, _, T, _, Shared, Impure),
    ddc_store:store_get(Shared, '$plan'(T), plan(Ids, _)),
    Ids \== [],
    findall(Id, ddc_store:store_match(Impure, '$swept'(Id, T), _), Own0),
    msort(Own0, Own), msort(Ids, Own),
    \+ ( member(Id, Ids), ddc_store:store_get(Shared, '$swept'(Id, T), _) ),
    filter_free(F).

%   Agreement is found by the thread that steps each group of particles
%   (ddc_particles:group_agreement/6) and combined after the step: with 1, 2 or 3
%   threads the ball's position, seen again, moves to the shared store;
%   the particles' own copies (the same value) stay until each particle
%   next steps, and are dropped then.
test(agreed_values_move_with_any_number_of_threads, [forall(member(K, [1, 2, 3]))]) :-
    program(File),
    filter_new(File, 30, 5, [engine(per_particle), threads(K)], F),
    frames(Frames), length(Pre, 6), append(Pre, [S7|_], Frames),
    maplist(step(F), Pre),          % the ball is seen again in the 6th frame
    particles_state(F, N, T, Ws, Shared, Impure),
    ddc_store:store_get(Shared, pos(ball)-T, V),
    \+ ddc_store:store_get(Impure, pos(ball)-T, _),
    ddc_store:store_get(Shared, '$moved'(T), Moved), memberchk(pos(ball)-T, Moved),
    forall(( between(1, N, I), arg(I, Ws, W), ddc_world:world_store(W, S) ),
           ( ddc_store:store_get(S, pos(ball)-T, V1), V1 == V )),
    step(F, S7),
    particles_state(F, _, _, Ws7, _, _),
    forall(( between(1, N, I), arg(I, Ws7, W), ddc_world:world_store(W, S) ),
           \+ ddc_store:store_get(S, pos(ball)-T, _)),
    filter_free(F).

:- end_tests(ddc_shared).

%   particles_state(+F, -N, -T, -Worlds, -SharedStore, -ImpureKeys): a
%   per-particle filter's state, read by the names of its fields.
particles_state(F, N, T, Ws, SS, Imp) :-
    ddc_filter:filter_state(F, St),
    ddc_particles:particles_size(St, N),
    ddc_particles:particles_time(St, T),
    ddc_particles:particles_worlds(St, Ws),
    ddc_particles:particles_shared(St, Sh),
    ddc_world:shared_store(Sh, SS),
    ddc_world:shared_impure_keys(Sh, Imp).
