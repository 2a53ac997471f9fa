/*  Tests of ddc_pool.pl: the group split, the seeds and the worker
    threads that both filter engines step their groups with.
*/

:- use_module(library(plunit)).
:- use_module(library(lists)).
:- use_module(library(apply)).
:- use_module('../../../prolog/ddc/runtime/ddc_pool').

:- begin_tests(ddc_pool).

test(bounds_cover_the_range_in_near_equal_groups) :-
    forall(( between(1, 40, N), between(1, 8, K) ),
           ( group_bounds(1, N, K, Bounds),
             findall(I, ( member(Lo-Hi, Bounds), between(Lo, Hi, I) ), Is),
             numlist(1, N, Is),
             maplist([Lo-Hi, S]>>(S is Hi-Lo+1), Bounds, Sizes),
             max_list(Sizes, Max), min_list(Sizes, Min),
             Max - Min =< 1 )).

test(bounds_leave_out_empty_groups) :-
    group_bounds(2, 3, 4, Bounds),
    assertion(Bounds == [2-2, 3-3]).

test(sizes_are_those_of_the_bounds) :-
    forall(( between(1, 30, N), between(1, N, K) ),
           ( group_sizes(N, K, Sizes),
             length(Sizes, K),
             sum_list(Sizes, N),
             group_bounds(1, N, K, Bounds),
             maplist([Lo-Hi, S]>>(S is Hi-Lo+1), Bounds, Sizes) )).

test(seeds_come_from_the_current_stream) :-
    set_random(seed(7)), group_seeds(3, S1),
    set_random(seed(7)), group_seeds(3, S2),
    set_random(seed(8)), group_seeds(3, S3),
    assertion(S1 == S2),
    assertion(S1 \== S3),
    length(S1, 2).

test(a_random_stream_of_its_own_leaves_the_callers_as_it_was) :-
    set_random(seed(1)), random_property(state(Caller)),
    with_random_stream(seed(7), random(X1), R1),
    random_property(state(After)),
    assertion(After == Caller),
    with_random_stream(seed(7), random(X2), R2),
    assertion(X1 == X2), assertion(R1 == R2),
    with_random_stream(state(R1), random(Y1), _),
    set_random(seed(7)), random(_), random(Y2),
    assertion(Y1 == Y2),
    catch(with_random_stream(seed(8), domain_error(x, y), _), _, true),
    random_property(state(AfterError)),
    set_random(seed(7)), random(_), random(_), random_property(state(Expected)),
    assertion(AfterError == Expected).

test(jobs_run_in_other_threads_and_come_back_in_order) :-
    thread_self(Me),
    findall(job(I, Out)-Out, between(1, 5, I), Jobs),
    pool_run(Local = here, Jobs, Outs),
    assertion(Local == here),
    length(Outs, 5),
    forall(nth1(I, Outs, O), ( O = I-Thread, assertion(Thread \== Me) )).

test(a_jobs_error_is_raised_after_every_job_came_back,
     [error(domain_error(job, 2))]) :-
    pool_run(true, [slow_job(1)-_, failing_job(2)-_, slow_job(3)-_], _).

test(the_local_error_comes_first, [error(domain_error(local, x))]) :-
    pool_run(domain_error(local, x), [failing_job(2)-_], _).

test(a_failing_job_is_an_error, [error(goal_failed(_), _)]) :-
    pool_run(true, [fail-_], _).

test(workers_survive_an_error) :-
    catch(pool_run(true, [failing_job(1)-_], _), _, true),
    pool_run(true, [job(1, Out)-Out], [Back]),
    assertion(Back = 1-_).

:- end_tests(ddc_pool).

% The jobs (called in the worker threads as user:Goal).
job(I, I-Thread) :- thread_self(Thread).
slow_job(_) :- sleep(0.05).
failing_job(I) :- domain_error(job, I).
