/*  ddc_pool.pl -- the per-particle filter's worker threads and group split.

    Part of the DDC engine (ddc.pl is the module users load).  A filter
    step's particles are split into contiguous groups, each stepped by a
    thread of its own from a seed drawn from the filter's random stream
    (ddc_particles.pl, step_groups/10).  This module holds that machinery,
    apart from what a group's job does: the split, the seeds, the worker
    threads (kept for the process) and the sending and collecting of jobs.
    (ddc_batch.pl has its own, batch_worker/2; the two are to become one.)
*/

:- module(ddc_pool,
          [ group_seeds/2,              % +K, -Seeds
            group_bounds/4,             % +From, +To, +K, -Bounds
            pool_start/5,               % +Queue, +Tag, :Goal, ?Out, -Thread
            pool_result/3               % +Queue, +Tag, -Out
          ]).

:- use_module(library(lists)).
:- use_module(library(apply)).

:- meta_predicate pool_start(+, +, 0, ?, -).

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

%!  pool_start(+Queue, +Tag, :Goal, ?Out, -Thread) is det.
%
%   Sends Goal (copied by the message) to worker thread Tag, which runs it
%   and answers Tag-Out on Queue: Out as Goal bound it, error(E) if Goal
%   raised E, error(failed(Goal)) if it failed.
pool_start(Q, Tag, Goal, Out, Thread) :-
    group_thread(Tag, Thread),
    thread_send_message(Thread, pool_job(Q, Tag, Goal, Out)).

%!  pool_result(+Queue, +Tag, -Out) is det.
%
%   Waits for the answer of worker Tag on Queue.
pool_result(Q, Tag, Out) :-
    thread_get_message(Q, Tag-Out).

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
        ->  (   var(E) -> Result = Out ; Result = error(E) )
        ;   Result = error(failed(Goal))
        ),
        catch(thread_send_message(Q, Tag-Result), _, true)
    ;   true
    ),
    group_loop.
