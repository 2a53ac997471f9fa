/*  plunit tests of the original DC system's directives and arithmetic
    (prolog/ddc/compat/dc_compat_load.pl, as ddc_load/1 uses them) and of the
    original's entry points (prolog/ddc/compat/dc_compat.pl).  Fixed seeds; tolerances
    of 3 standard errors.
*/
:- use_module('../../../prolog/ddc/compat/dc_compat').
:- use_module('../../../prolog/ddc/compat/dc_compat_load').
:- use_module('../../../prolog/ddc', [query/3]).
:- use_module(library(plunit)).
:- use_module(library(lists)).

program(Lines, File) :-
    tmp_file_stream(text, File, S),
    forall(member(L, Lines), format(S, "~w~n", [L])),
    close(S).

header(['% an old program',
        ':- use_module(\'../distributionalclause.pl\').',
        ':- use_module(\'../random/sampling.pl\').']).

%   warnings(:Goal, -Messages): Goal's warnings (dc_compat(...) terms).
:- dynamic caught/1.
:- multifile user:message_hook/3.
user:message_hook(dc_compat(M, W), warning, _) :-
    caught(_), !, assertz(caught(dc_compat(M, W))).
warnings(G, Ms) :-
    setup_call_cleanup(assertz(caught(start)), G, true),
    findall(M, caught(dc_compat(M, _)), Ms),
    retractall(caught(_)).

:- begin_tests(dc_compat_load).

test(conjunction_of_setters_accepted_silently) :-
    header(H),
    append(H, [':- set_options(default),set_inference(backward(lw)).',
               ':- initialization(init).',
               'coin ~ finite([0.2:true,0.8:false]).'], Ls),
    program(Ls, F),
    warnings(ddc_load(F), Ms),
    assertion(Ms == []),
    query(coin ~= true, P, [samples(100), seed(1)]),
    assertion(abs(P - 0.2) < 1e-9).

test(ignored_option_warns_once_with_file_and_line) :-
    header(H),
    append(H, [':- set_options(default), set_lifted(true).',
               'coin ~ finite([0.2:true,0.8:false]).'], Ls),
    program(Ls, F),
    warnings((ddc_load(F), ddc_load(F)), Ms),
    assertion(Ms == [option_ignored(set_lifted(true), lifted)]),
    findall(W, dc_compat_load:warned_(set_lifted(true), W), Ws),
    assertion(Ws == [F:4]).

test(unknown_option_value_is_an_error_at_its_line) :-
    header(H),
    append(H, [':- set_inference(backward(magic)).'], Ls),
    program(Ls, F),
    catch(ddc_load(F), error(ddc(Cause, Where), _), true),
    assertion(Cause == bad_directive(set_inference(backward(magic)))),
    assertion(Where == F:4).

test(set_options_takes_the_first_applicable_clause) :-
    header(H),
    append(H, [':- set_options(default).',
               'a ~ finite([0.5:1,0.5:2]).',
               'h ~ val(one) := a ~= 1.',
               'h ~ val(any) := true.'], Ls),
    program(Ls, F),
    ddc_load(F),
    query(h ~= one, P, [samples(4000), seed(2)]),
    assertion(abs(P - 0.5) =< 3*sqrt(0.25/4000)).

test(overlap_is_still_an_error_without_the_original_header) :-
    program(['a ~ finite([0.5:1,0.5:2]).',
             'h ~ val(one) := a ~= 1.',
             'h ~ val(any) := true.'], F),
    ddc_load(F),
    catch(query(h ~= one, _, [samples(100), seed(2)]), error(ddc(Cause, _), _), true),
    assertion(Cause = overlapping_clauses(_, _)).

test(random_in_arithmetic) :-
    original_arithmetic((x(X) :- Y is random*2, Y < random, X = random), T),
    assertion(T == (x(X) :- Y is random_float*2, Y < random_float, X = random)).

test(random_in_a_body_is_a_uniform_draw) :-
    program(['r ~ val(X) := X is random.'], F),
    ddc_load(F),
    query((r ~= X, X < 0.3), P, [samples(4000), seed(3)]),
    assertion(abs(P - 0.3) =< 3*sqrt(0.21/4000)).

test(old_programs_logfinite_weight_and_internal_reads_rewritten) :-
    C0 = (observation(o):t+1 ~ logfinite([W:_]) :=
              p:t+1 ~= [_|W], current(q) ~= 1, \+(observation(o) ~= _)),
    original_program([t((:- set_options(default)), 1), t(C0, 2), t(test :- step([observation(o) ~= 1]), 3)],
                     [_, t(C, 2), t(Plain, 3)]),
    assertion(C = (observation(o):t+1 ~ logweight(_) :=
                       p:t+1 ~= [_|_], q:t ~= 1, \+ dc_observation(o, _))),
    assertion(Plain == (test :- step([observation(o) ~= 1]))),
    %   without the original's set_options/1 the program is this engine's
    original_program([t(C0, 1)], [t(C1, 1)]),
    assertion(C1 =@= C0).

:- end_tests(dc_compat_load).

:- begin_tests(dc_compat_entry_points).

tutorial :-
    source_file(tutorial, This),
    file_directory_name(This, Dir),
    atomic_list_concat([Dir, '/../../../prolog/examples/dc/tutorial.pl'], F0),
    absolute_file_name(F0, F),
    ddc_load(F).

test(query7_sums) :-
    tutorial, set_random(seed(1)),
    query([], [], (nballs ~= N, N > 5), 4000, P, S, Sum),
    assertion(abs(P - S/Sum) < 1e-12),
    assertion(abs(P - 0.5) =< 3*sqrt(0.25/4000)).

test(eval_query_distribution_counts_every_proof) :-
    tutorial, set_random(seed(1)),
    %   ball(X) has nballs proofs: E[number of X with ball(X), X = 1] = 1
    eval_query_distribution(X, [], [], ball(X), 4000, D, _, Sum),
    assertion(Sum =:= 1.0),
    memberchk(P1:1, D), assertion(abs(P1 - 1.0) < 1e-9),
    memberchk(P10:10, D), assertion(abs(P10 - 0.1) =< 3*sqrt(0.09/4000)).

test(eval_query_valuelist) :-
    tutorial, set_random(seed(1)),
    eval_query_valuelist([], [], coin ~= X, X, 1000, L, 1.0),
    memberchk(PT:true, L), assertion(abs(PT - 0.2) =< 3*sqrt(0.16/1000)).

test(step_without_init_is_an_existence_error) :-
    retractall(dc_compat:current_belief_(_, _)),
    catch(step_particle([], [], 10), error(E, _), true),
    assertion(E == existence_error(filter, init_particle)).

test(blackboard) :-
    bb_put(sum, 1.5), bb_get(sum, V), assertion(V == 1.5),
    bb_delete(sum, V2), assertion(V2 == 1.5),
    assertion(\+ bb_get(sum, _)).

test(density_gaussian) :-
    densityGaussian(0, 0.01, 0.0, D),
    assertion(abs(D - 3.98942280401433) < 1e-9).

test(delta_t_and_eval_average_particle) :-
    header(H),
    append(H, [':- set_options(default).',
               'x:0 ~ val(0.0).',
               'x:t+1 ~ val(Y) := x:t ~= X, deltaT(D), Y is X + D.'], Ls),
    program(Ls, F),
    ddc_load(F),
    init_particle(10),
    step_particle([], [], 10, 0.5),
    step_particle([], [], [], 10, 0.25),
    eval_average_particle([A:k], k, current(x), 10, [P:k]),
    assertion(abs(A - 0.75) < 1e-9),
    assertion(abs(P - 1.0) < 1e-9),
    get_loglikelihood(LL), assertion(abs(LL) < 1e-9).

test(wrong_particle_count_is_a_domain_error) :-
    header(H),
    append(H, [':- set_options(default).', 'x:0 ~ val(0.0).'], Ls),
    program(Ls, F),
    ddc_load(F),
    init_particle(10),
    catch(step_particle([], [], 20), error(E, _), true),
    assertion(E == domain_error(particles(10), 20)).

:- end_tests(dc_compat_entry_points).
