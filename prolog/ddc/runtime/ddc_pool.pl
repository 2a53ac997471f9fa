/** <module> The filters' worker threads and group split

Part of the DDC system (ddc.pl is the module users load).  With
threads(K), K > 1, a filter's particles are split into K contiguous
groups, each with a random stream of its own seeded from the filter's,
and a step runs the groups at the same time: the first in the calling
thread, each other one as a job of a worker thread.  Both engines do
so (ddc_particles.pl, step_groups/10; ddc_batch.pl, batch_step/4); this
module holds what they share, apart from what a group's job does: the
split, the seeds, the worker threads (kept for the process, shared by
every filter) and the sending and collecting of jobs; a filter's (or
a group's) own random stream; and how many of a step's first
particles are checked for overlapping clauses.
*/

:- module(ddc_pool,
          [ group_seeds/2,              % +K, -Seeds
            group_bounds/4,             % +From, +To, +K, -Bounds
            group_sizes/3,              % +N, +K, -Sizes
            pool_run/3,                 % :Local, +Jobs, -Outs
            with_random_stream/3,       % +Start, :Goal, -R
            overlap_checked_particles/1 % -N
          ]).

:- use_module(library(lists)).
:- use_module(library(apply)).

:- meta_predicate pool_run(0, :, -), with_random_stream(+, 0, -).

%   Arithmetic compiled to virtual-machine instructions (local to this
%   file; see ddc.pl).
:- set_prolog_flag(optimise, true).

%!  group_seeds(+K, -Seeds) is det.
%
%   A seed for each of K groups but the first (which goes on with the
%   filter's own random stream), drawn from the current random stream.
group_seeds(K, Seeds) :-
    K1 is K-1,
    length(Seeds, K1),
    maplist(random_seed, Seeds).

random_seed(S) :-
    random_between(0, 0x3fffffffffffffff, S).

%!  with_random_stream(+Start, :Goal, -R) is semidet.
%
%   Runs Goal with Prolog's random stream set by set_random(Start)
%   (seed(S) or state(R0)), R the stream's state after Goal; the caller's
%   stream is restored, also when Goal fails or raises an error.  A filter,
%   and each group of one, owns its stream: its draws do not depend on what
%   other filters or queries drew in between.
with_random_stream(Start, Goal, R) :-
    random_property(state(Saved)),
    call_cleanup(( set_random(Start), Goal, random_property(state(R)) ),
                 set_random(state(Saved))).

%!  group_bounds(+From, +To, +K, -Bounds) is det.
%
%   From..To in K contiguous groups Lo-Hi of sizes differing by at most one
%   (empty ones left out).
group_bounds(From, To, K, Bounds) :-
    Size is To-From+1,
    findall(Lo-Hi,
            ( between(0, K, G0), G0 < K,
              Lo is From + (Size*G0) // K,
              Hi is From + (Size*(G0+1)) // K - 1,
              Hi >= Lo ),
            Bounds).

%!  group_sizes(+N, +K, -Sizes) is det.
%
%   The sizes of the K groups of group_bounds(1, N, K, Bounds), in order
%   (K =< N: none is empty).
group_sizes(N, K, Sizes) :-
    group_bounds(1, N, K, Bounds),
    maplist(bound_size, Bounds, Sizes).

bound_size(Lo-Hi, Size) :-
    Size is Hi-Lo+1.

%!  overlap_checked_particles(-N) is det.
%
%   Overlapping clauses are looked for in the first N particles of every
%   filter step, by both engines (ddc_particles.pl's step_range_at/10,
%   ddc_batch.pl's check_list/3): the horizon of that check, a constant of
%   the engine.  Checking a particle costs an evaluation of each rival
%   clause's body in it, so the check looks at a few particles, not at all
%   of them.  (Static queries have a horizon of their own: ddc_world.pl's
%   overlap_checked_worlds/1.)
overlap_checked_particles(20).

%!  pool_run(:Local, +Jobs:list, -Outs:list) is det.
%
%   Runs the jobs at the same time as Local: each job Goal-Out of Jobs,
%   the I-th one sent (copied by the message) to worker thread I, which
%   runs Goal and sends back its Out as Goal bound it; Local runs in the
%   calling thread meanwhile.  Outs are the jobs' Outs in the order of
%   Jobs.  Every job is waited for, also when Local raises an error; then
%   the first error is raised, Local's first, then the jobs' in order.
%
%   @error whatever Local or a job's Goal raised;
%          goal_failed(Goal) if a job's Goal failed.
pool_run(Local, M:Jobs, Outs) :-
    length(Jobs, K),
    numlist(1, K, Tags),
    message_queue_create(Q),
    setup_call_cleanup(
        maplist(pool_start(Q, M), Tags, Jobs),
        (   catch(Local, E, true),
            maplist(pool_result(Q), Tags, Results)
        ),
        message_queue_destroy(Q)),      % (a worker still busy after an abort
                                        % finds the queue gone, and goes on)
    (   nonvar(E) -> throw(E) ; true ),
    maplist(job_out, Results, Outs).

%   pool_start(+Queue, +Module, +Tag, +Goal-Out): Goal (of Module) sent to
%   worker thread Tag, which answers Tag-done(Out) (Out as Goal bound it)
%   or Tag-error(E) on Queue.
pool_start(Q, M, Tag, Goal-Out) :-
    group_thread(Tag, Thread),
    thread_send_message(Thread, pool_job(Q, Tag, M:Goal, Out)).

pool_result(Q, Tag, Result) :-
    thread_get_message(Q, Tag-Result).

job_out(error(E), _) :- !, throw(E).
job_out(done(Out), Out).

%   group_thread(+Tag, -Thread): the worker thread for groups Tag.  Workers
%   are kept for the life of the process (a new thread for every step would
%   grow its stacks from nothing each time) and shared by all filters: a
%   worker runs one job at a time.
group_thread(Tag, Alias) :-
    atom_concat('$ddc_group_worker_', Tag, Alias),
    with_mutex('$ddc_group_workers',
               (   catch(thread_property(Alias, status(running)), _, fail)
               ->  true
               ;   thread_create(group_loop, _, [alias(Alias), detached(true)])
               )).

%   A worker: runs the jobs it is sent, one after the other, and sends back
%   what each bound (or the error).  (A queue gone, after an abort of the
%   step that sent the job, is ignored.)
group_loop :-
    thread_get_message(Job),
    (   Job = pool_job(Q, Tag, Goal, Out)
    ->  (   catch(Goal, E, true)
        ->  (   var(E) -> Result = done(Out) ; Result = error(E) )
        ;   Result = error(error(goal_failed(Goal), context(ddc_pool:pool_run/3, _)))
        ),
        catch(thread_send_message(Q, Tag-Result), _, true)
    ;   true
    ),
    group_loop.
