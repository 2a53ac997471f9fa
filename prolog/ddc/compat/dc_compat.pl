/*  dc_compat.pl -- the original Distributional Clauses system's entry
    points (DC and its particle filter DCPF, written for YAP), over this
    engine, so that programs written for the original run unmodified:

        swipl prolog/ddc/compat/dc_compat.pl OLD_PROGRAM.pl
        ?- test_balls2(1000).

    The program's own header (use_module of '../distributionalclause.pl',
    '../dcpf.pl', '../random/sampling.pl', the option setters,
    `:- initialization(init).`) is accepted; its distributional clauses are
    compiled by ddc_load/1 and its plain Prolog (the test predicates) stays
    in module user, where the predicates below answer its calls.
*/

:- module(dc_compat,
          [ init/0,
            set_options/1, set_inference/1, set_query_propagation/1,
            set_lifted/1, set_raoblackwellisation/1, set_debug/1,
            set_current2nextcopy/1,
            query/7,                    % +PosEv, +NegEv, +Query, +N, -P, -SuccSum, -Sum
            eval_query/7,               % same as query/7
            eval_query_backward_lw/8,   % +PosEv, +NegEv, +Query, ?X, +N, -P, -SuccSum, -Sum
            eval_query_backward_eval/8,
            eval_query_backward/8,
            eval_query_distribution/8,  % ?X, +PosEv, +NegEv, +Query, +N, -P, -Succ, -Sum
            eval_query_valuelist/7,     % +PosEv, +NegEv, +Query, ?X, +N, -P, -Sum
            test_query/6,               % +PosEv, +NegEv, +Query, ?X, +N, -P
            generate_backward/2,        % +Query, -Facts
            generate_backward/3,        % +Given, +Query, -Facts
            init_particle/1,            % +N
            init_particle/2,            % +Obs, +N
            init_particle/3,            % +Actions, +Obs, +N
            step_particle/2,            % +Obs, +N
            step_particle/3,            % +Actions, +Obs, +N
            step_particle/4,            % +Actions, +Obs, +N, +Delta
            step_particle/5,            % +Actions, +Obs, +Constraints, +N, +Delta
            step_particle_aux/3, step_particle_aux/4, step_particle_aux/5,
            step_particle_ps/2, step_particle_ps/3, step_particle_ps/4,
            eval_query_particle/3,      % +Query, +N, -P
            eval_query_particle2/4,     % ?X, +Query, +N, -List
            eval_average_particle/5,    % -Avg, ?X, +Query, +N, -P
            get_loglikelihood/1,        % -LogLikelihood
            printp/1,                   % +I
            particle_recorded/3,        % ?Key, ?Term, -Ref
            reset_loglikelihood/0,
            densityGaussian/4,          % +Mean, +Var, +X, -Density
            remove_duplicates/2,        % +List, -Set
            bb_put/2, bb_get/2, bb_delete/2,
            eraseall/1,                 % +Key
            op(700, xfx, ~),
            op(700, xfx, ~=),
            op(1105, xfx, :=),
            op(1105, xfx, <-),
            op(1150, xfx, pr)
          ]).

:- reexport('../../ddc.pl', [ddc_load/1, ddc_load/2, ddc_program/1, query/5, query/8]).
:- use_module('../filter/ddc_belief').
:- use_module(dc_compat_load).
:- use_module('../lang/ddc_programs', [program_file_/2]).
:- use_module('../runtime/ddc_query', [no_program_loaded/1]).
:- use_module(library(lists)).
:- use_module(library(apply)).
:- use_module(library(error)).
:- use_module(library(pairs)).
:- use_module(library(statistics)).
:- use_module(library(terms)).

/** <module> The original DC/DCPF entry points

Static queries (the original's module distributionalclause): query/5 and
query/8 (from ddc.pl), query/7, eval_query/7, eval_query_backward_lw/8
(and its classic and plain variants, all the same estimator here),
eval_query_distribution/8, eval_query_valuelist/7, test_query/6 (prints
the estimate and its time; the original halted the program here).

The particle filter (the original's module dcpf) is one filter of the
program loaded last, held by this module as the original held its
particles: init_particle/1,2,3, step_particle/2..5 (and the _aux and _ps
variants: the same filter step here), eval_query_particle/3,
eval_query_particle2/4, eval_average_particle/5, get_loglikelihood/1,
reset_loglikelihood/0.  Plot predicates written for the original find
particle I through `bb_get(dcpf:offset, O)` (always 0) and
`distributionalclause:proof_query_backward(I, Goal)`.

Answers are this engine's, which differ from the original where the
original was wrong (docs/dc-compat.md has the table).
*/

:- dynamic
    dc_source_/2,                  % dc_source_(File, LoadStream): loaded through the original's header
    current_belief_/2,             % current_belief_(Belief, N)
    ll_offset_/1.                  % log-likelihood before reset_loglikelihood/0

                 /*******************************
                 *      LOADING IN SWIPL        *
                 *******************************/

%   The hook (user:term_expansion/2) is at the end of this file, so that
%   it is in place only once the predicates it calls are.
%
%   original_term(+Term, +File, -Expanded): at the original's header,
%   File is compiled as a DC program (ddc_load/1, from its text on disk);
%   from then on its DC clauses and option directives are dropped from
%   module user (they live in the program's module) and its plain clauses
%   get the original's arithmetic.
original_term((:- use_module(S)), F, []) :-
    original_library(S), !,
    style_check(-singleton),        % (the original's programs are full of them; for this file only)
    prolog_load_context(stream, In),
    (   dc_source_(F, In)
    ->  true                        % the header's second line, this load
    ;   retractall(dc_source_(F, _)),
        assertz(dc_source_(F, In)),
        catch(ddc_load(F), E, print_message(error, E))
    ).
original_term(T, F, X) :-
    dc_source_(F, _),
    (   dc_clause(T)
    ->  X = []
    ;   T = (:- D), original_directive_quiet(D)
    ->  X = []
    ;   original_arithmetic(T, X1),
        particle_records(X1, X),
        X \== T
    ).

%   particle_records(+Term0, -Term): recorded/3 goals become
%   particle_recorded/3 (the original kept particle I under the key I of
%   YAP's recorded database; the plot predicates of its examples read it).
particle_records(T0, T) :-
    mapsubterms(particle_record, T0, T).

particle_record(T, dc_compat:particle_recorded(K, G, R)) :-
    nonvar(T), T = recorded(K, G, R).

original_library(S) :-
    ground(S),
    (   S = library(_) -> fail ; true ),
    term_to_atom(S, A0),
    (   atom(S) -> A = S ; A = A0 ),
    file_base_name(A, B),
    file_name_extension(Base, _, B),
    memberchk(Base, [distributionalclause, dcpf, sampling]).

dc_clause(T) :- var(T), !, fail.
dc_clause(_ ~ _).
dc_clause(_ := _).
dc_clause(_ <- _).
dc_clause(_ pr _).

%   The option setters were checked (and warned about) by ddc_load/1.
original_directive_quiet(D) :-
    catch(original_directive_syntax(D), _, fail).

original_directive_syntax((A, B)) :- !,
    original_directive_syntax(A), original_directive_syntax(B).
original_directive_syntax(D) :-
    compound(D), compound_name_arity(D, N, 1),
    memberchk(N, [set_options, set_inference, set_query_propagation, set_debug,
                  set_lifted, set_raoblackwellisation, set_current2nextcopy]).

                 /*******************************
                 *            OPTIONS           *
                 *******************************/

%!  init is det.
%
%   The original's initialisation (clear the sample store, compile the
%   program).  Here the program is compiled when it is loaded and every
%   query starts from fresh worlds, so there is nothing to do.
init.

%!  set_options(+Options) is det.
%!  set_inference(+Mode) is det.
%!  set_query_propagation(+Bool) is det.
%!  set_lifted(+Bool) is det.
%!  set_raoblackwellisation(+Bool) is det.
%!  set_debug(+Bool) is det.
%!  set_current2nextcopy(+Bool) is det.
%
%   Called as goals (at the top level, or by a test predicate): accepted
%   as the directives are (dc_compat_load.pl), with the same warnings.
set_options(X) :- setter(set_options(X)).
set_inference(X) :- setter(set_inference(X)).
set_query_propagation(X) :- setter(set_query_propagation(X)).
set_lifted(X) :- setter(set_lifted(X)).
set_raoblackwellisation(X) :- setter(set_raoblackwellisation(X)).
set_debug(X) :- setter(set_debug(X)).
set_current2nextcopy(X) :- setter(set_current2nextcopy(X)).

setter(D) :-
    (   original_directive(D, goal:0, _) -> true
    ;   domain_error(original_option, D)
    ).

                 /*******************************
                 *        STATIC QUERIES        *
                 *******************************/

%!  query(+PosEv:list, +NegEv:list, +Query, +N:integer, -P:float, -SuccSum:float, -Sum:float) is det.
%!  eval_query(+PosEv:list, +NegEv:list, +Query, +N:integer, -P:float, -SuccSum:float, -Sum:float) is det.
%
%   P = P(Query | PosEv, not NegEv) from N samples; SuccSum and Sum are
%   the weight sums of the samples where Query holds and of all samples
%   that count (P = SuccSum/Sum).
query(PosEv, NegEv, Q, N, P, SuccSum, Sum) :-
    query(PosEv, NegEv, Q, 1, N, P, SuccSum, Sum).

eval_query(PosEv, NegEv, Q, N, P, SuccSum, Sum) :-
    query(PosEv, NegEv, Q, 1, N, P, SuccSum, Sum).

%!  eval_query_backward_lw(+PosEv:list, +NegEv:list, +Query, ?X, +N:integer, -P:float, -SuccSum:float, -Sum:float) is det.
%!  eval_query_backward_eval(+PosEv:list, +NegEv:list, +Query, ?X, +N:integer, -P:float, -SuccSum:float, -Sum:float) is det.
%!  eval_query_backward(+PosEv:list, +NegEv:list, +Query, ?X, +N:integer, -P:float, -SuccSum:float, -Sum:float) is det.
%
%   P = E[X * 1(Query) | evidence] (query/8): with X = 1 the probability
%   of Query.  The original's three estimators are one here.
eval_query_backward_lw(PosEv, NegEv, Q, X, N, P, S, Sum) :-
    query(PosEv, NegEv, Q, X, N, P, S, Sum).
eval_query_backward_eval(PosEv, NegEv, Q, X, N, P, S, Sum) :-
    query(PosEv, NegEv, Q, X, N, P, S, Sum).
eval_query_backward(PosEv, NegEv, Q, X, N, P, S, Sum) :-
    query(PosEv, NegEv, Q, X, N, P, S, Sum).

%!  eval_query_distribution(?X, +PosEv:list, +NegEv:list, +Query, +N:integer, -P:list, -Succ:float, -Sum:float) is det.
%
%   P = [Prob:Value, ...], for each value of X the expected number of
%   proofs of Query in which X has that value, given the evidence (every
%   proof of Query in a world counts, as in the original).  The weights
%   are normalised: Sum = 1.0 and Succ is the sum of the Prob.
eval_query_distribution(X, PosEv, NegEv, Q, N, P, Succ, 1.0) :-
    evidence(PosEv, NegEv, Ev),
    distribution(Ev, findall(X, Q, Xs), Xs, Dist, [samples(N)]),
    findall(V-Pr, ( member(Pr:Xs1, Dist), member(V, Xs1) ), VPs0),
    keysort(VPs0, VPs),
    group_pairs_by_key(VPs, Groups),
    findall(S:V, ( member(V-Ps, Groups), sum_list(Ps, S) ), P),
    foldl(add_prob, P, 0.0, Succ).

add_prob(S:_, A0, A) :- A is A0 + S.

%!  eval_query_valuelist(+PosEv:list, +NegEv:list, +Query, ?X, +N:integer, -P:list, -Sum:float) is det.
%
%   P = [Weight:Value, ...]: the value of X at the first proof of Query,
%   weighted, given the evidence; here grouped by value and normalised
%   (Sum = 1.0), which is the same distribution as the original's one
%   entry per sample.
eval_query_valuelist(PosEv, NegEv, Q, X, N, P, 1.0) :-
    evidence(PosEv, NegEv, Ev),
    distribution(Ev, Q, X, P, [samples(N)]).

%!  test_query(+PosEv:list, +NegEv:list, +Query, ?X, +N:integer, -P:float) is det.
%
%   Estimates P = E[X * 1(Query) | evidence] and prints it with the time
%   it took.  (The original compared five estimators and then halted the
%   program; there is one estimator here, and the program goes on.)
test_query(PosEv, NegEv, Q, X, N, P) :-
    call_time(query(PosEv, NegEv, Q, X, N, P, S, Sum), Time),
    format("lw(~w,~w,~w)  % ~3f s~n", [P, S, Sum, Time.cpu]).

%!  generate_backward(+Query, -Facts:list) is semidet.
%
%   Proves Query in one sampled world of the program loaded last; Facts is
%   what the world holds: `h ~= V` for untimed, `h:T ~= V` for time-indexed
%   values (derived atoms as `h ~= true`).  Fails if Query fails in the
%   world drawn.
generate_backward(Q, Facts) :-
    (   ddc_program(M) -> true ; no_program_loaded(dc_compat:generate_backward/2) ),
    ddc:ddc_sample_world(M, Q, [], Entries),
    foldl(world_fact, Entries, Facts, []).

%!  generate_backward(+Given:list, +Query, -Facts:list) is semidet.
%
%   As generate_backward/2, in a world that holds Given first: values
%   `h ~= V`, `h:T ~= V`, `current(h) ~= V` (h at time 0), `next(h) ~= V`
%   (time 1), `prior(h) ~= V`, and plain facts (`action(move(1,1,0))`),
%   which the program's bodies read as a filter step's actions.  Facts
%   lists Given's values too, as the original listed every recorded fact.
generate_backward(Given, Q, Facts) :-
    must_be(list, Given),
    (   ddc_program(M) -> true ; no_program_loaded(dc_compat:generate_backward/3) ),
    foldl(given_entry, Given, Vs-Fs, []-[]),
    ddc:ddc_sample_world(M, Q, [values(Vs), facts(Fs)], Entries),
    foldl(world_fact, Entries, Facts, []).

given_entry(G, [X-T-V|Vs]-Fs, Vs-Fs) :-
    nonvar(G), G = (R ~= V), !,
    must_be(ground, V),
    given_key(R, X, T).
given_entry(G, Vs-[G|Fs], Vs-Fs) :-
    must_be(callable, G).

given_key(R, _, _) :- var(R), !, instantiation_error(R).
given_key(current(X), X, 0) :- !.
given_key(next(X), X, 1) :- !.
given_key(prior(X), X, 0) :- !.
given_key(X:T0, X, T) :- !, ( T0 == t -> T = 0 ; T0 == t+1 -> T = 1 ; must_be(integer, T0), T = T0 ).
given_key(X, X, u).

%   (A variable found undefined in the world, '$undef', is left out.)
world_fact(_-_-V, Fs, Fs) :- V == '$undef', !.
world_fact(X-u-V, [X ~= V|Fs], Fs) :- !.
world_fact(X-T-V, [X:T ~= V|Fs], Fs).

evidence(PosEv, NegEv, Ev) :-
    must_be(list, PosEv),
    must_be(list, NegEv),
    findall(\+ G, member(G, NegEv), Negs),
    append(PosEv, Negs, Ev).

%!  densityGaussian(+Mean:number, +Var:number, +X:number, -D:float) is det.
%
%   The density of N(Mean, Var) (Var the variance) at X.
densityGaussian(M, V, X, D) :-
    must_be(number, M), must_be(number, V), must_be(number, X),
    (   V > 0 -> true ; domain_error(positive_variance, V) ),
    D is exp(-((X-M)**2)/(2*V)) / sqrt(2*pi*V).

%!  remove_duplicates(+List:list, -Set:list) is det.
remove_duplicates(L, S) :-
    list_to_set(L, S).

                 /*******************************
                 *        PARTICLE FILTER       *
                 *******************************/

%!  init_particle(+N:integer) is det.
%!  init_particle(+Obs:list, +N:integer) is det.
%!  init_particle(+Actions:list, +Obs:list, +N:integer) is det.
%
%   A new filter of N particles of the program loaded last, drawn from its
%   time-0 clauses (replacing the previous filter).  The seed is drawn
%   from Prolog's random generator, so set_random(seed(S)) first repeats a
%   run.  Observations and actions given here are only visible to the
%   prior, as in the original, and do not weigh the particles; here they
%   are not visible either (the prior clauses of the original's examples
%   do not read them), so they must be [].
init_particle(N) :-
    must_be(positive_integer, N),
    (   ddc_program(M) -> true ; no_program_loaded(dc_compat:init_particle/1) ),
    program_file_(M, File),
    (   current_belief_(B0, _) -> catch(belief_free(B0), _, true) ; true ),
    retractall(current_belief_(_, _)),
    retractall(ll_offset_(_)),
    Seed is random(1 << 30),
    belief_new(File, [particles(N), seed(Seed)], B),
    assertz(current_belief_(B, N)),
    assertz(ll_offset_(0.0)),
    bb_put(dcpf:offset, 0).

init_particle(Obs, N) :-
    init_particle([], Obs, N).
init_particle(Actions, Obs, N) :-
    must_be(list, Actions), must_be(list, Obs),
    (   Actions == [], Obs == []
    ->  init_particle(N)
    ;   domain_error(empty_list_at_time_0, Actions-Obs)
    ).

%!  step_particle(+Obs:list, +N:integer) is det.
%!  step_particle(+Actions:list, +Obs:list, +N:integer) is det.
%!  step_particle(+Actions:list, +Obs:list, +N:integer, +Delta:number) is det.
%!  step_particle(+Actions:list, +Obs:list, +Constraints:list, +N:integer, +Delta:number) is det.
%
%   One filter step to t+1 with the actions (`action(null)`, ...) and the
%   observations (`observation(up) ~= wall`, ...): predict, weigh by the
%   observations, resample when the effective sample size falls below
%   0.9 N (ddc_belief:belief_step/4).  As in the original, `deltaT(Delta)`
%   holds during the step (default 1), unless the program defines deltaT/1
%   itself; Constraints are ignored, as they were.  N must be the number
%   of particles of init_particle/1.
step_particle(Obs, N) :-
    step_particle([], Obs, [], N, 1).
step_particle(Actions, Obs, N) :-
    step_particle(Actions, Obs, [], N, 1).
step_particle(Actions, Obs, N, Delta) :-
    step_particle(Actions, Obs, [], N, Delta).
step_particle(Actions, Obs, _Constraints, N, Delta) :-
    must_be(list, Actions), must_be(list, Obs), must_be(number, Delta),
    belief(N, B),
    ddc_program(M),
    observation_facts(Obs, OFacts),     % the untimed reads (dc_compat_load.pl)
    append(Actions, OFacts, Facts0),
    (   current_predicate(M:deltaT/1)
    ->  Facts = Facts0              % the program's own deltaT/1 stays (the original wiped it)
    ;   Facts = [deltaT(Delta)|Facts0]
    ),
    belief_step(B, Obs, Facts).

%   observation_facts(+Obs, -Facts): dc_observation(O, V) for each
%   `observation(O) ~= V` of the step, which the original recorded in the
%   particles and its programs read untimed in clause bodies.
observation_facts(Obs, Facts) :-
    findall(dc_observation(O, V), member(observation(O) ~= V, Obs), Facts).

%!  step_particle_aux(+Actions:list, +Obs:list, +N:integer) is det.
%!  step_particle_ps(+Obs:list, +N:integer) is det.
%
%   The original's auxiliary and partitioned-sampling steps: the same
%   posterior, so the same step here (step_particle/5).
step_particle_aux(Actions, Obs, N) :- step_particle(Actions, Obs, [], N, 1).
step_particle_aux(Actions, Obs, N, Delta) :- step_particle(Actions, Obs, [], N, Delta).
step_particle_aux(Actions, Obs, C, N, Delta) :- step_particle(Actions, Obs, C, N, Delta).
step_particle_ps(Obs, N) :- step_particle([], Obs, [], N, 1).
step_particle_ps(Actions, Obs, N) :- step_particle(Actions, Obs, [], N, 1).
step_particle_ps(Actions, Obs, N, Delta) :- step_particle(Actions, Obs, [], N, Delta).

belief(N, B) :-
    (   current_belief_(B, N0)
    ->  (   N =:= N0 -> true
        ;   domain_error(particles(N0), N)
        )
    ;   existence_error(filter, init_particle)
    ).

%!  eval_query_particle(+Query, +N:integer, -P:float) is det.
%
%   P = the weighted fraction of particles in which Query holds now
%   (`current(h) ~= V` or `h:t ~= V`).
eval_query_particle(Q, N, P) :-
    belief(N, B),
    timed_goal(Q, G),
    belief_probability(B, G, P).

%!  eval_query_particle2(?X, +Query, +N:integer, -List:list) is det.
%
%   List = [P:Value, ...]: for each value of X, the weighted fraction of
%   particles in which Query has a proof with that value (every proof in a
%   particle counts, so the P need not sum to 1), in the standard order of
%   the values.
eval_query_particle2(X, Q, N, L) :-
    belief(N, B),
    belief_filter(B, F),
    timed_goal(Q, G),
    filter_values(F, Xs, findall(X, G, Xs), Values),
    belief_weights(B, Ws),
    findall(V-W, ( nth1(I, Values, Xs1), nth1(I, Ws, W),
                   sort(Xs1, Set), member(V, Set) ), VWs0),
    keysort(VWs0, VWs),
    group_pairs_by_key(VWs, Groups),
    findall(S:V, ( member(V-Ws1, Groups), sum_list(Ws1, S) ), L).

%!  eval_average_particle(-Avg:list, ?X, +Query, +N:integer, -P:list) is det.
%
%   Query is a random variable term (`current(reward(X))`).  Avg =
%   [Mean:Value, ...], for each value of X the weighted mean of Query's
%   value over the particles where it is defined; P = [Prob:Value, ...],
%   the weighted fraction of those particles.
eval_average_particle(Avg, X, Q, N, P) :-
    belief(N, B),
    belief_filter(B, F),
    timed_goal(Q ~= V, G),
    filter_values(F, Ps, findall(X-V, G, Ps), Values),
    belief_weights(B, Ws),
    findall(Xv-(W-V), ( nth1(I, Values, Ps1), nth1(I, Ws, W), member(Xv-V, Ps1) ), Es0),
    keysort(Es0, Es),
    group_pairs_by_key(Es, Groups),
    findall(M:Xv, ( member(Xv-WVs, Groups), weighted_mean(WVs, M) ), Avg),
    findall(S:Xv, ( member(Xv-WVs, Groups), pairs_keys(WVs, Ws1), sum_list(Ws1, S) ), P).

%   timed_goal(+Goal0, -Goal): the original's current(h) written h:t, as
%   both of the filter's engines read it (Goal shares Goal0's variables).
timed_goal(T0, T) :-
    mapsubterms(timed_term, T0, T).

timed_term(T, X:t) :-
    nonvar(T), T = current(X), nonvar(X).

weighted_mean(WVs, M) :-
    foldl(add_weighted, WVs, 0.0-0.0, SW-SWV),
    (   SW > 0 -> M is SWV / SW ; M = 0.0 ).

add_weighted(W-V, SW0-S0, SW-S) :-
    must_be(number, V),
    SW is SW0 + W, S is S0 + W*V.

%!  get_loglikelihood(-LL:float) is det.
%
%   The log-likelihood of the observations since init_particle/1 (or
%   reset_loglikelihood/0): the sum over the steps of the log of the
%   weighted mean likelihood of their observations.
get_loglikelihood(LL) :-
    current_belief_(B, _), !,
    belief_log_likelihood(B, LL0),
    ll_offset_(Off),
    LL is LL0 - Off.
get_loglikelihood(_) :-
    existence_error(filter, init_particle).

%!  reset_loglikelihood is det.
reset_loglikelihood :-
    current_belief_(B, _), !,
    belief_log_likelihood(B, LL0),
    retractall(ll_offset_(_)),
    assertz(ll_offset_(LL0)).
reset_loglikelihood.

%   distributionalclause:proof_query_backward(+I, ?Goal): Goal holds in
%   particle I (1-based) now; Goal's variables are bound to their values
%   there, one proof after another on backtracking (tracking.pl's and
%   minimalexample.pl's plotdata/1 go through every object).  For the
%   original's plot predicates.
distributionalclause:proof_query_backward(I, Goal) :-
    dc_compat:particle_goal(I, Goal).

%   distributionalclause:proof_query_backward_lazy(+I, +TempKey, ?Goal):
%   the original's lazy proof of Goal in particle I into the throw-away
%   store TempKey; the same as proof_query_backward/2 here (a query never
%   changes a particle, so there is no store to give).
distributionalclause:proof_query_backward_lazy(I, _TempKey, Goal) :-
    dc_compat:particle_goal(I, Goal).

%!  eraseall(+Key) is det.
%
%   YAP's eraseall/1: erases every record of Key in SWI-Prolog's recorded
%   database.  The original's programs call it on its throw-away particle
%   store (`eraseall(tempparticle)`) before a query; particles themselves
%   are not in that database here, so erasing a particle key changes no
%   particle.
eraseall(Key) :-
    must_be(nonvar, Key),
    forall(recorded(Key, _, Ref), erase(Ref)).

%!  particle_recorded(?Key, ?Term, -Ref) is nondet.
%
%   The original's `recorded(I, current(h) ~= V, _)` for particle I (1..N
%   of the filter): each solution of Term in particle I, Ref = particle(I);
%   any other key is SWI-Prolog's recorded database (recorded/3).
particle_recorded(K, G, Ref) :-
    integer(K), current_belief_(B, N), K >= 1, K =< N, !,
    belief_filter(B, F),
    timed_goal(G, G0),
    copy_term(G-G0, G1-Q),
    filter_values(F, L, findall(G1, Q, L), Values),
    nth1(K, Values, Sols),
    Ref = particle(K),
    member(G, Sols).
particle_recorded(K, G, Ref) :-
    recorded(K, G, Ref).

%!  printp(+I:integer) is det.
%
%   Prints the values particle I holds now (`current(h) ~= V`, one a
%   line; untimed values `h ~= V`), as the original's printp/1.
printp(I) :-
    must_be(positive_integer, I),
    (   current_belief_(_, N) -> true ; existence_error(filter, init_particle) ),
    (   I =< N -> true ; domain_error(particle(1, N), I) ),
    ddc_program(M),
    M:'$ddc_info'(info(_, _, RvU, RvT, _, _, _)),
    forall(( member(Na/A, RvT), functor(H, Na, A) ),
           forall(particle_recorded(I, current(H) ~= V, _),
                  format("~q~n", [current(H) ~= V]))),
    forall(( member(Na/A, RvU), \+ memberchk(Na/A, RvT), functor(H, Na, A) ),
           forall(particle_recorded(I, H ~= V, _),
                  format("~q~n", [H ~= V]))).

%   dcpf:bb_get(offset, O), as the original's plot predicates call it
%   (also bb_get(dcpf:offset, O)): O = 0, particle I is key I.
dcpf:bb_get(K, V) :-
    (   K == offset -> V = 0 ; dc_compat:bb_get(K, V) ).

particle_goal(I, Goal) :-
    must_be(positive_integer, I),
    current_belief_(B, N), !,
    (   I =< N -> true ; domain_error(particle(1, N), I) ),
    belief_filter(B, F),
    timed_goal(Goal, G0),
    copy_term(Goal-G0, Goal1-G),
    filter_values(F, L, findall(Goal1, G, L), Values),
    nth1(I, Values, Sols),
    member(Goal, Sols).

                 /*******************************
                 *          BLACKBOARD          *
                 *******************************/

%!  bb_put(+Key, +Value) is det.
%!  bb_get(+Key, -Value) is semidet.
%!  bb_delete(+Key, -Value) is semidet.
%
%   YAP's blackboard, which the original's example programs use for their
%   own sums (bb_get(dcpf:offset, O) gives 0: particle I is key I).
bb_put(K, V) :-
    bb_key(K, A),
    nb_setval(A, V).
bb_get(K, V) :-
    bb_key(K, A),
    nb_current(A, V0),
    V = V0.
bb_delete(K, V) :-
    bb_key(K, A),
    nb_current(A, V0),
    nb_delete(A),
    V = V0.

bb_key(K, A) :-
    must_be(ground, K),
    format(atom(A), 'dc_compat_bb ~q', [K]).

                 /*******************************
                 *             HOOK             *
                 *******************************/

:- multifile user:term_expansion/2.
:- dynamic user:term_expansion/2.

user:term_expansion(T, X) :-
    nonvar(T),
    prolog_load_context(source, F),
    dc_compat:original_term(T, F, X).
