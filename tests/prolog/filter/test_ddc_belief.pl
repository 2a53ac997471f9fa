/*  plunit tests of prolog/ddc/filter/ddc_belief.pl: the weighted belief of a filter
    for swipl users (the same rules as bridge.Filter, kept in Prolog).

    Probabilistic tests use fixed seeds; their tolerances are a few
    standard errors of a sample of the effective size the belief reports.
*/
:- use_module('../../../prolog/ddc/filter/ddc_belief').
:- use_module(library(plunit)).
:- use_module(library(lists)).
:- use_module(library(apply)).

example(Name, Path) :-
    module_property(ddc_belief, file(F)),
    file_directory_name(F, Dir),
    atomic_list_concat([Dir, '/../../examples/filter/', Name], Path).

%   k standard errors of a proportion p estimated from an effective sample
%   of size E (p(1-p) at least 1e-4, as the Python tests).
binomial_tolerance(P, E, Tol) :-
    Tol is 5 * sqrt(max(P*(1-P), 1.0e-4) / E).

%   The effective size of a sample that went through a step of effective
%   size ESS and then, perhaps, N-particle resampling.
effective(ESS, N, E) :-
    E is 1 / (1/ESS + 1/N).

pit_frames([ null-false, up-true, down-false, right-true ]).

pit_step(B, Move-Breeze, Step) :-
    belief_step(B, [observation(breeze) ~= Breeze], [action(Move)], Step).

:- begin_tests(ddc_belief).

test(wumpus_one_step_gives_p_wall_0_857143) :-
    example('wumpus.pl', W),
    N = 1500,
    belief_new(W, [particles(N), seed(11)], B),
    belief_step(B, [observation(up) ~= wall, observation(right) ~= free],
                [action(null)], Step),
    assertion(Step.time == 1),
    belief_time(B, 1),
    belief_probability(B, maze(0,1):t ~= wall, P),
    Exact is 0.4*0.9 / (0.4*0.9 + 0.6*0.1),
    effective(Step.ess, N, E),
    binomial_tolerance(Exact, E, Tol),
    assertion(abs(P - Exact) < Tol),
    belief_distribution(B, maze(0,1):t, Dist),
    length(Dist, 2),
    memberchk(PW:wall, Dist),
    assertion(memberchk(_:free, Dist)),
    assertion(abs(PW - P) < 1.0e-9),
    sum_probabilities(Dist, S),
    assertion(abs(S - 1) < 1.0e-9),
    belief_free(B).

test(pit_world_from_the_jsonl_file) :-
    example('pit_world.pl', Prog),
    example('pit_world.jsonl', Frames),
    N = 2000,
    belief_new(Prog, [particles(N), seed(5)], B),
    Smallest = smallest(N),
    belief_run(B, Frames, keep_smaller_ess(Smallest)),
    belief_time(B, 4),
    belief_zero_weight_events(B, 0),
    belief_distribution(B, (A, C, D),
                        (maze(0,2):t ~= A, maze(1,1):t ~= C, maze(2,0):t ~= D), Joint),
    %   0/1 likelihoods: at worst as many distinct ancestors as the
    %   smallest step ESS, then N-particle resampling
    arg(1, Smallest, ESS),
    effective(ESS, N, E),
    forall(member(V-Exact, [(pit,pit,pit)-(1/29), (pit,pit,free)-(4/29),
                            (pit,free,pit)-(4/29), (free,pit,pit)-(4/29),
                            (free,pit,free)-(16/29)]),
           ( ( memberchk(P:V, Joint) -> true ; P = 0.0 ),
             X is Exact,
             binomial_tolerance(X, E, Tol),
             assertion(abs(P - X) < Tol) )),
    forall(member(_:V1, Joint),                 % the other combinations have weight 0
           assertion(memberchk(V1, [(pit,pit,pit), (pit,pit,free), (pit,free,pit),
                                    (free,pit,pit), (free,pit,free)]))),
    forall(member(Cell-Exact, [(1,1)-(4/29), (2,0)-(20/29), (0,2)-(20/29)]),
           ( Cell = (CX, CY),
             belief_probability(B, maze(CX,CY):t ~= free, P),
             X is Exact,
             binomial_tolerance(X, E, Tol),
             assertion(abs(P - X) < Tol) )),
    belief_probability(B, maze(0,1):t ~= free, P01),
    assertion(abs(P01 - 1) < 1.0e-9),
    belief_free(B).

test(random_walk_matches_the_kalman_filter_for_20_steps) :-
    example('random_walk.pl', Prog),
    N = 1000,
    belief_new(Prog, [particles(N), seed(3)], B),
    set_random(seed(2024)),
    observations(20, 0.0, Ys),
    kalman(Ys, 0.0, 1.0, Ms),
    forall(nth1(K, Ys, Y),
           ( nth1(K, Ms, M-V),
             belief_step(B, [observation(y) ~= Y], [], Step),
             belief_mean(B, x:t, Mean, Var),
             effective(Step.ess, N, E),
             assertion(abs(Mean - M) < 6 * sqrt(V / E)),
             assertion(abs(Var - V) < 6 * V * sqrt(2 / E)) )),
    belief_samples(B, x:t, Samples),
    length(Samples, N),
    foldl([W-X, S0, S1]>>(S1 is S0 + W*X), Samples, 0.0, WeightedSum),
    belief_mean(B, x:t, Mean20, _),
    assertion(abs(WeightedSum - Mean20) < 1.0e-9),
    belief_log_likelihood(B, LL),
    assertion(LL < 0),
    belief_free(B).

%   Without resampling the weights carry the evidence: the weighted mean
%   still follows the Kalman filter, and the running log-likelihood is the
%   exact one, sum log N(y; predicted mean, predicted variance + 1), within
%   5 standard errors of its estimate (about sqrt(1/ESS) per step).
test(weights_without_resampling_and_the_log_likelihood) :-
    example('random_walk.pl', Prog),
    N = 1000,
    belief_new(Prog, [particles(N), seed(4), resample_threshold(0.0)], B),
    set_random(seed(7)),
    observations(8, 0.0, Ys),
    kalman(Ys, 0.0, 1.0, Ms),
    exact_log_likelihood(Ys, 0.0, 1.0, 0.0, Exact),
    foldl(unresampled_step(B, N), Ys, Ms, 0.0, InvESS),
    belief_ess(B, ESS),
    assertion(ESS < 0.9 * N),
    belief_weights(B, Ws),
    sum_list(Ws, SumW),
    assertion(abs(SumW - 1) < 1.0e-9),
    belief_log_likelihood(B, LL),
    assertion(abs(LL - Exact) < 5 * sqrt(InvESS)),
    belief_free(B).

test(every_particle_weight_zero_keeps_the_pre_step_particles) :-
    example('pit_world.pl', Prog),
    N = 200,
    belief_new(Prog, [particles(N), seed(2)], B),
    pit_step(B, null-false, _),
    belief_filter(B, F),
    filter_values(F, (A, C), (maze(1,0):t ~= A, maze(0,1):t ~= C), Before),
    belief_log_likelihood(B, LL),
    with_output_to(string(_),
                   belief_step(B, [observation(breeze) ~= maybe], [action(null)], Step)),
    assertion(Step.zero_weight == true),
    belief_zero_weight_events(B, 1),
    belief_time(B, 1),
    filter_values(F, (A, C), (maze(1,0):t ~= A, maze(0,1):t ~= C), After),
    assertion(After == Before),
    belief_weights(B, Ws),
    U is 1/N,
    assertion(forall(member(W, Ws), abs(W - U) < 1.0e-12)),
    belief_log_likelihood(B, LL),
    pit_frames([_|Rest]),
    forall(member(Fr, Rest), pit_step(B, Fr, _)),
    belief_time(B, 4),
    belief_zero_weight_events(B, 1),
    belief_free(B).

test(same_seed_same_answers) :-
    example('random_walk.pl', Prog),
    run_walk(Prog, 17, S1, LL1),
    run_walk(Prog, 17, S2, LL2),
    assertion(S1 == S2),
    assertion(LL1 == LL2),
    run_walk(Prog, 18, S3, _),
    assertion(S1 \== S3).

test(a_bad_frame_names_file_and_line_and_keeps_the_steps_before_it) :-
    example('pit_world.pl', Prog),
    tmp_file_stream(text, Frames, Out),
    format(Out, '~w~n~n~w~n~w~n',
           [ '{"actions": ["action(null)"], "observations": ["observation(breeze) ~= false"]}',
             '{"actions": ["action(up)"], "observations": [{"observation": "breeze", "value": "true"}]}',
             '{"actions": ["action(down)"], "observations": ["observation(breeze ~= false"]}' ]),
    close(Out),
    belief_new(Prog, [particles(100), seed(1)], B),
    catch(belief_run(B, Frames), E, true),
    assertion(nonvar(E)),
    message_text(E, Text),
    atomic_list_concat([Frames, ':4: '], Where),
    assertion(sub_string(Text, 0, _, _, Where)),
    assertion(sub_string(Text, _, _, _, "syntax error")),
    belief_time(B, 2),                          % lines 1 and 3 were stepped
    belief_step(B, [observation(breeze) ~= false], [action(down)]),
    belief_time(B, 3),
    catch(belief_step(B, [observation(smell) ~= true], [action(up)]), E2, true),
    assertion(nonvar(E2)),
    belief_time(B, 3),
    belief_free(B).

test(an_unknown_key_is_an_error) :-
    example('pit_world.pl', Prog),
    tmp_file_stream(text, Frames, Out),
    format(Out, '{"obs": []}~n', []),
    close(Out),
    belief_new(Prog, [particles(10), seed(1)], B),
    catch(belief_run(B, Frames), E, true),
    message_text(E, Text),
    assertion(sub_string(Text, _, _, _, ":1: unknown key")),
    belief_free(B).

test(systematic_copies_floor_or_ceil_of_n_w) :-
    Ws = [0.05, 0.5, 0.2, 0.25],
    forall(member(U, [0.0, 0.3, 0.999]),
           ( resample_indices(systematic, Ws, [U, 0.5, 0.5, 0.5], Is),
             length(Is, 4),
             forall(nth0(I, Ws, W),
                    ( aggregate_all(count, member(I, Is), C),
                      assertion((C =:= floor(4*W) ; C =:= ceiling(4*W))) )) )).

test(a_position_past_a_cumulative_sum_short_of_1_takes_the_last_particle) :-
    Ws = [0.3, 0.3, 0.3999999],
    resample_indices(systematic, Ws, [0.9999999], Is),
    assertion(Is == [1, 2, 2]),              % positions 0.33, 0.67, 0.99999997
    resample_indices(multinomial, Ws, [0.99999995, 0.1, 0.5], Ms),
    assertion(Ms == [0, 1, 2]).

test(residual_keeps_the_whole_copies) :-
    Ws = [0.05, 0.5, 0.2, 0.25],
    resample_indices(residual, Ws, [0.9, 0.1, 0.5, 0.5], Is),
    assertion(Is == [1, 1, 2, 3]),              % 2 copies of 1 and 1 of 3; one drawn from the residuals 0.2, 0, 0.8, 0
    resample_indices(multinomial, Ws, [0.9, 0.01, 0.5, 0.06], Ms),
    assertion(Ms == [0, 1, 1, 3]).

test(read_frame_file_gives_the_terms_of_each_non_blank_line) :-
    tmp_file_stream(text, Frames, Out),
    format(Out, '{"observations": ["observation(up) ~~= wall", {"observation": "pos(b)", "value": [0.5, [1, "Ab"], true]}], "actions": ["action(null)"]}~n~n', []),
    format(Out, '{"comment": "nothing seen"}~n', []),
    close(Out),
    read_frame_file(Frames, Fs),
    assertion(Fs == [ frame(1, [ observation(up) ~= wall,
                                 observation(pos(b)) ~= (0.5, (1, 'Ab'), true) ],
                            [action(null)]),
                      frame(3, [], []) ]).

test(read_frame_file_names_file_line_and_item) :-
    forall(member(Line-Expected,
                  [ '{"observations": ["a", 3]}'-":2: observations[2]: an observation is term text",
                    '{"actions": ["  "]}'-":2: actions[1]: empty term text",
                    '{"actions": ["f(X)"]}'-":2: actions[1]: not ground",
                    '{"observations": ["f("]}'-":2: observations[1]: syntax error in \"f(\": ",
                    '[1]'-":2: a line must be a JSON object",
                    '{"observations": [{"observation": "x", "value": {}}]}'-":2: observations[1]: cannot use"
                  ]),
           ( tmp_file_stream(text, Frames, Out),
             format(Out, '{}~n~w~n', [Line]),
             close(Out),
             catch(read_frame_file(Frames, _), E, true),
             assertion(nonvar(E)),
             message_text(E, Text),
             atom_concat(Frames, Expected, Start),
             assertion(sub_string(Text, 0, _, _, Start)) )).

:- end_tests(ddc_belief).

message_text(Term, S) :-
    '$messages':translate_message(Term, Lines, []),
    with_output_to(string(S), print_message_lines(current_output, '', Lines)).

keep_smaller_ess(Smallest, Step) :-
    get_dict(ess, Step, ESS),
    arg(1, Smallest, E0),
    E is min(E0, ESS),
    nb_setarg(1, Smallest, E).

sum_probabilities(Dist, S) :-
    foldl([P:_, S0, S1]>>(S1 is S0 + P), Dist, 0.0, S).

%   Observations of the random walk x_{t+1} = x_t + N(0, 0.5), y = x + N(0, 1).
observations(0, _, []) :- !.
observations(K, X0, [Y|Ys]) :-
    gauss(G1), gauss(G2),
    X is X0 + sqrt(0.5)*G1,
    Y is X + G2,
    K1 is K - 1,
    observations(K1, X, Ys).

gauss(G) :-
    U1 is 1 - random_float, U2 is random_float,
    G is sqrt(-2*log(U1)) * cos(2*pi*U2).

kalman([], _, _, []).
kalman([Y|Ys], M0, P0, [M-P|Out]) :-
    P1 is P0 + 0.5,
    Gain is P1 / (P1 + 1.0),
    M is M0 + Gain*(Y - M0),
    P is (1 - Gain)*P1,
    kalman(Ys, M, P, Out).

unresampled_step(B, N, Y, M-V, I0, I) :-
    belief_step(B, [observation(y) ~= Y], [], Step),
    assertion(Step.resampled == false),
    belief_mean(B, x:t, Mean, _),
    effective(Step.ess, N, E),
    assertion(abs(Mean - M) < 6 * sqrt(V / E)),
    I is I0 + 1 / Step.ess.

exact_log_likelihood([], _, _, LL, LL).
exact_log_likelihood([Y|Ys], M0, P0, LL0, LL) :-
    P1 is P0 + 0.5,
    S is P1 + 1.0,
    LL1 is LL0 - 0.5*((Y - M0)**2/S + log(2*pi*S)),
    Gain is P1 / S,
    M is M0 + Gain*(Y - M0),
    P is (1 - Gain)*P1,
    exact_log_likelihood(Ys, M, P, LL1, LL).

run_walk(Prog, Seed, Samples, LL) :-
    belief_new(Prog, [particles(200), seed(Seed)], B),
    forall(member(Y, [0.3, -0.2, 0.9, 1.4]), belief_step(B, [observation(y) ~= Y], [])),
    belief_samples(B, x:t, Samples),
    belief_log_likelihood(B, LL),
    belief_free(B).
