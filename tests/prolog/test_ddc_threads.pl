/*  plunit tests of filters used from several threads and of reloads
    while a filter is live (prolog/ddc/filter/ddc_filter.pl, filter_new/5: "Threads
    and reloads"): a filter's particles live in an engine of their own that
    any thread may run, its program in a module of its own that no load
    replaces.  Every run is compared with the same filter made and stepped
    in the main thread alone (same program, seed, engine and threads).
*/
:- use_module('../../prolog/ddc').
:- use_module(library(plunit)).
:- use_module(library(lists)).
:- use_module(library(apply)).

write_program(Lines, File) :-
    tmp_file_stream(text, File, S),
    forall(member(L, Lines), format(S, "~w~n", [L])),
    close(S).

%   pit_world(-File): a copy of prolog/examples/filter/pit_world.pl (an
%   agent moves, feels a breeze next to a pit; the maze is drawn lazily),
%   which a test may overwrite.
:- prolog_load_context(directory, Dir),
   directory_file_path(Dir, '../../prolog/examples/filter/pit_world.pl', Example),
   absolute_file_name(Example, Abs),
   assertz(pit_world_example(Abs)).

pit_world(File) :-
    pit_world_example(Example),
    tmp_file_stream(text, File, S),
    close(S),
    copy_file(Example, File).

pit_frames([null-false, up-true, down-false, right-true]).

%   The setups: (engine, threads) as filter_new/5 options.
setup([engine(batched)]).
setup([engine(per_particle)]).
setup([engine(per_particle), threads(2)]).

%   run(+File, +Options, +Seed, -Run): a filter made and stepped over the
%   pit frames, then freed; Run = run(LogWeights, Positions, Maze11).
run(File, Options, Seed, Run) :-
    filter_new(File, 100, Seed, Options, F),
    steps(F, Run),
    filter_free(F).

steps(F, run(LWs, Ps, Ms)) :-
    pit_frames(Frames),
    foldl(step(F), Frames, [], LWs),
    snapshot(F, Ps, Ms).

step(F, A-B, LWs0, [LW|LWs0]) :-
    filter_step(F, [observation(breeze) ~= B], [action(A)], LW).

snapshot(F, Ps, Ms) :-
    filter_values(F, P, position ~= P, Ps),
    filter_values(F, M, maze(1,1) ~= M, Ms).

%   in_thread_result(:Goal, ?Template, -Result): Goal run (once) in a new
%   thread; Result is Template at its solution (a thread's bindings are its
%   own: they come back in a message); its exception is raised here.
in_thread_result(Goal, Template, Result) :-
    thread_self(Me),
    thread_create(( catch(( Goal, Out = true(Template) ), E, Out = error(E)),
                    thread_send_message(Me, '$result'(Out)) ),
                  Id, [detached(false)]),
    thread_get_message('$result'(Out)),
    thread_join(Id, _),
    (   Out = true(Result) -> true
    ;   Out = error(E) -> throw(E)
    ).

:- begin_tests(ddc_threads).

% More threads than particles to share among them: the groups that would
% be empty are not made (the per-particle engine failed the step).
test(more_threads_than_particles_steps,
     [forall(( member(N-K, [1-2, 2-2, 3-3, 3-4, 5-8]),
               member(Engine, [per_particle, batched]) ))]) :-
    pit_world(File),
    filter_new(File, N, 7, [threads(K), engine(Engine)], F),
    filter_step(F, [observation(breeze) ~= false], [action(up)], LWs),
    filter_step(F, [observation(breeze) ~= true], [action(right)], LWs2),
    filter_free(F),
    length(LWs, N),
    length(LWs2, N).

test(made_and_stepped_in_a_thread_gives_the_main_threads_particles,
     [forall(setup(Options))]) :-
    pit_world(File),
    run(File, Options, 5, Reference),
    in_thread_result(run(File, Options, 5, Run), Run, OffMain),
    OffMain == Reference,
    Reference = run([LW1|_], Ps, _), length(LW1, 100), length(Ps, 100).

test(two_filters_in_two_threads_at_once, [forall(setup(Options))]) :-
    pit_world(File),
    run(File, Options, 1, R1), run(File, Options, 2, R2),
    R1 \== R2,
    thread_self(Me),
    forall(member(Seed, [1, 2]),
           thread_create(( run(File, Options, Seed, R),
                           thread_send_message(Me, ran(Seed, R)) ), _, [detached(true)])),
    thread_get_message(ran(1, T1)),
    thread_get_message(ran(2, T2)),
    T1 == R1, T2 == R2.

test(a_handle_is_valid_in_every_thread) :-
    pit_world(File),
    Options = [engine(per_particle), threads(2)],
    run(File, Options, 3, run(LWs, Ps, Ms)),
    filter_new(File, 100, 3, Options, F),                   % made here,
    pit_frames([Fr1, Fr2, Fr3, Fr4]),
    in_thread_result(foldl(step(F), [Fr1, Fr2], [], L2), L2, LWs2),    % stepped in one thread,
    in_thread_result(foldl(step(F), [Fr3, Fr4], LWs2, L4), L4, LWs4),  % then in another,
    LWs4 == LWs,
    in_thread_result(snapshot(F, P1, M1), P1-M1, Ps1-Ms1),  % queried in a third,
    Ps1 == Ps, Ms1 == Ms,
    in_thread_result(filter_free(F), true, true),           % freed in a fourth
    catch(filter_time(F, _), error(existence_error(ddc_filter, G), _), true),
    G == F.

test(one_filter_stepped_from_two_threads_takes_one_step_at_a_time) :-
    %   eight steps, four from each thread, all with the same frame: whatever
    %   their order each step is whole, and the particles are those of eight
    %   steps in one thread
    pit_world(File),
    Frames = [null-false, null-false, null-false, null-false],
    filter_new(File, 100, 4, [engine(per_particle)], A),
    foldl(step(A), Frames, [], _), foldl(step(A), Frames, [], _),
    snapshot(A, Ps, Ms), filter_free(A),
    filter_new(File, 100, 4, [engine(per_particle)], B),
    thread_create(foldl(step(B), Frames, [], _), T1),
    thread_create(foldl(step(B), Frames, [], _), T2),
    thread_join(T1, true), thread_join(T2, true),
    filter_time(B, 8),
    snapshot(B, Ps, Ms),
    filter_free(B).

test(a_reload_of_a_changed_file_leaves_a_live_filter_its_program,
     [forall(member(Engine, [batched, per_particle]))]) :-
    write_program(['x:0 ~ val(1).', 'x:t+1 ~ val(X) := x:t ~= X.'], File),
    filter_new(File, 10, 1, [engine(Engine)], Old),
    write_program(['x:0 ~ val(2).', 'x:t+1 ~ val(Y) := x:t ~= X, Y is X + 10.'], New),
    copy_file(New, File),
    ddc_load(File, M),                                  % the static program: the new text
    query(x:0 ~= 2, P, [program(M), samples(10)]), P =:= 1.0,
    filter_new(File, 10, 1, [engine(Engine)], Young),
    filter_step(Old, [], [], _), filter_step(Young, [], [], _),
    filter_values(Old, X, x ~= X, Xs), maplist(==(1), Xs),
    filter_values(Young, Y, x ~= Y, Ys), maplist(==(12), Ys),
    filter_free(Old), filter_free(Young).

test(a_reloader_thread_does_not_break_a_live_filter, [forall(setup(Options))]) :-
    pit_world(File),
    numlist(1, 30, Rounds),
    filter_new(File, 50, 8, Options, A),
    forall(member(_, Rounds), filter_step(A, [observation(breeze) ~= false], [action(null)], _)),
    snapshot(A, Ps, Ms), filter_free(A),
    filter_new(File, 50, 8, Options, B),
    flag(test_ddc_reloads, _, 0),
    thread_create(reload_until_stopped(File), R),
    forall(member(_, Rounds),
           (   thread_send_message(R, step),            % a load between any two steps
               thread_get_message(reloaded),
               filter_step(B, [observation(breeze) ~= false], [action(null)], _)
           )),
    thread_send_message(R, stop),
    thread_join(R, true),
    flag(test_ddc_reloads, N, N), N =:= 30,
    snapshot(B, Ps, Ms),
    filter_free(B).

reload_until_stopped(File) :-
    thread_get_message(Msg),
    (   Msg == stop
    ->  true
    ;   ddc_load(File),
        flag(test_ddc_reloads, N, N+1),
        thread_send_message(main, reloaded),
        reload_until_stopped(File)
    ).

test(loads_into_one_module_from_two_threads_do_not_interleave) :-
    write_program(['a ~ finite([0.25:1, 0.75:2]).', 'b ~ val(1).'], F1),
    write_program(['a ~ finite([0.5:1, 0.5:2]).', 'b ~ val(2).'], F2),
    M = test_ddc_threads_shared_module,
    thread_create(forall(between(1, 30, _), ddc_load(F1, M)), T1),
    thread_create(forall(between(1, 30, _), ddc_load(F2, M)), T2),
    thread_join(T1, true), thread_join(T2, true),
    %   the module holds one of the two programs, whole: P(a = 1) and
    %   P(b = 1) are those of the same one (exact: weighted, not sampled)
    query(a ~= 1, Pa, [program(M), samples(5)]),
    query(b ~= 1, Pb, [program(M), samples(5)]),
    (   Pa =:= 0.25 -> Pb =:= 1.0 ; Pa =:= 0.5, Pb =:= 0.0 ).

test(an_error_names_the_programs_file_not_the_filters_module) :-
    write_program(['x:0 ~ val(1).', 'b:t+1 ~ val(1) := true.', 'b:t+1 ~ val(2) := true.'],
                  File),
    forall(member(Engine, [batched, per_particle]),
           (   filter_new(File, 5, 1, [engine(Engine)], F),
               catch(filter_step(F, [], [], _), error(ddc(Cause, Where), _), true),
               filter_free(F),
               Cause = overlapping_clauses(_, OtherFile:3),
               Where = File:2, OtherFile == File
           )).

test(free_and_a_failed_new_leave_nothing_behind) :-
    pit_world(File),
    filter_new(File, 5, 1, F),
    once(ddc_filter:filter_engine_(F, _, M, File)),
    once(current_predicate(M:_)),
    filter_free(F),
    \+ ddc_filter:filter_engine_(F, _, _, _),
    \+ current_predicate(M:_),
    \+ ddc_programs:program_file_(M, _),
    filter_free(F),                                     % (again: nothing to do)
    write_program(['x:0 ~ val(1).', 'x:t+1 ~ val(X) := x:t ~= X, (.'], Bad),
    aggregate_all(count, ddc_filter:filter_engine_(_, _, _, _), Before),
    catch(filter_new(Bad, 5, 1, _), error(syntax_error(_), context(ddc_source:_, Bad:2)), true),
    aggregate_all(count, ddc_filter:filter_engine_(_, _, _, _), Before).

:- end_tests(ddc_threads).
