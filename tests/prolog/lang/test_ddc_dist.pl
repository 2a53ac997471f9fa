/*  plunit tests of prolog/ddc/lang/ddc_dist.pl: sample moments against the analytic
    ones (fixed seeds, tolerance 5 standard errors of the sample size),
    densities against hand-computed values, normalisation, parameter
    errors and their messages, reproducibility, determinism.
*/

:- use_module('../../../prolog/ddc/lang/ddc_dist').
:- use_module(library(plunit)).
:- use_module(library(lists)).
:- use_module(library(apply)).

% draws(+Dist, +N, +Seed, -Xs)
draws(D, N, Seed, Xs) :-
    set_random(seed(Seed)),
    length(Xs, N),
    maplist(dist_sample(D), Xs).

mean_var(Xs, M, V) :-
    length(Xs, N),
    sum_list(Xs, S),
    M is S/N,
    foldl([X, A0, A]>>(A is A0 + (X-M)**2), Xs, 0, SS),
    V is SS/(N-1).

%   moments_ok(+Xs, +Mean, +Var): the sample mean is within 5 standard
%   errors sqrt(Var/N) of Mean, the sample variance within 5 standard
%   errors sqrt((m4 - Var^2)/N) of Var (m4 the sample 4th central moment).
moments_ok(Xs, Mean, Var) :-
    length(Xs, N),
    mean_var(Xs, M, V),
    foldl([X, A0, A]>>(A is A0 + (X-M)**4), Xs, 0, S4),
    M4 is S4/N,
    SEM is sqrt(Var/N),
    SEV is sqrt(max(M4 - V*V, 1.0e-300)/N),
    (   abs(M - Mean) =< 5*SEM,
        abs(V - Var) =< 5*SEV
    ->  true
    ;   format(user_error, "mean ~w (want ~w, se ~w), var ~w (want ~w, se ~w)~n",
               [M, Mean, SEM, V, Var, SEV]),
        fail
    ).

near(X, Y) :- near(X, Y, 1.0e-9).
near(X, Y, Tol) :-
    (   abs(X - Y) =< Tol*(1 + abs(Y))
    ->  true
    ;   format(user_error, "~w is not close to ~w~n", [X, Y]),
        fail
    ).

ninf(X) :- float(X), X < 0, X =:= -inf.

log_density(D, X, LP) :- dist_log_density(D, X, LP).

%   midpoint_integral(+Dist, +Lo, +Hi, +N, -I): midpoint rule of the
%   density of Dist over [Lo,Hi].
midpoint_integral(D, Lo, Hi, N, I) :-
    H is (Hi - Lo)/N,
    N1 is N - 1,
    aggregate_all(sum(P),
                  ( between(0, N1, K),
                    X is Lo + (K + 0.5)*H,
                    dist_log_density(D, X, LP),
                    \+ ninf(LP),
                    P is exp(LP) ),
                  S),
    I is S*H.

:- begin_tests(ddc_dist_moments).

% (Dist, Mean, Variance) of every 1-D numeric distribution
moment_case(finite([0.9:1, 0.05:5, 0.05:6]), 1.45, V) :-
    V is 0.9*1 + 0.05*25 + 0.05*36 - 1.45**2.
moment_case(propfinite([1:0, 3:10]), 7.5, V) :- V is 0.75*100 - 56.25.
moment_case(logfinite([0:0, L3:1]), 0.75, 0.1875) :- L3 is log(3).
moment_case(uniform([2, 4, 9]), 5, V) :- V is (4 + 16 + 81)/3 - 25.
moment_case(uniform(1:10), 5.5, 8.25).
moment_case(gaussian(2, 0.5), 2, 0.5).
moment_case(gaussian([-1], [3]), -1, 3).
moment_case(contUniform(-1, 3), 1, V) :- V is 16/12.
moment_case(beta(2, 3), 0.4, 0.04).
moment_case(beta(0.5, 0.5), 0.5, 0.125).
moment_case(gamma(2.5, 1.5), 3.75, 5.625).
moment_case(gamma(0.4, 2), 0.8, 1.6).
moment_case(invgamma(5, 2), 0.5, V) :- V is 4/(16*3).
moment_case(student(6, 1, 2), 1, V) :- V is 2*6/4.
moment_case(student(8), 0, V) :- V is 8/6.
moment_case(poisson(3.5), 3.5, 3.5).
moment_case(poisson(0), 0, 0).
moment_case(poisson(60), 60, 60).
moment_case(exponential(4), 0.25, 0.0625).

test(one_dimensional, [forall(moment_case(D, M, V))]) :-
    dist_check(D),
    draws(D, 20000, 42, Xs),
    (   V =:= 0
    ->  forall(member(X, Xs), X =:= M)
    ;   moments_ok(Xs, M, V)
    ),
    dist_mean(D, DM),
    near(DM, M).

test(bool) :-
    draws(bool(0.3), 20000, 7, Xs),
    aggregate_all(count, member(true, Xs), T),
    aggregate_all(count, member(X, Xs), 20000),
    \+ ( member(X, Xs), X \== true, X \== false ),
    abs(T/20000 - 0.3) =< 5*sqrt(0.3*0.7/20000).

test(uniform_over_terms) :-
    draws(uniform([a, b, a, c]), 20000, 8, Xs),
    aggregate_all(count, member(a, Xs), A),
    abs(A/20000 - 0.5) =< 5*sqrt(0.25/20000).

test(finite_zero_probability_never_drawn) :-
    draws(finite([0.5:a, 0.0:b, 0.5:c, 0.0:d]), 5000, 9, Xs),
    \+ memberchk(b, Xs),
    \+ memberchk(d, Xs).

test(logfinite_minus_infinity_never_drawn) :-
    NInf is -inf,
    draws(logfinite([NInf:a, 0:b, -(inf):c]), 500, 9, Xs),
    forall(member(X, Xs), X == b).

test(val, [true(Xs == [foo(1), foo(1)])]) :-
    draws(val(foo(1)), 2, 1, Xs).

test(multivariate_gaussian) :-
    % covariance [[2,0.6,0],[0.6,0.5,0.1],[0,0.1,1]], mean (1,-1,0)
    Cov = [2, 0.6, 0, 0.6, 0.5, 0.1, 0, 0.1, 1],
    D = gaussian([1, -1, 0], Cov),
    dist_check(D),
    draws(D, 20000, 3, Ts),
    forall(member(T, Ts), T = (_, _, _)),
    maplist([(A, _, _), A]>>true, Ts, As),
    maplist([(_, B, _), B]>>true, Ts, Bs),
    maplist([(_, _, C), C]>>true, Ts, Cs),
    moments_ok(As, 1, 2),
    moments_ok(Bs, -1, 0.5),
    moments_ok(Cs, 0, 1),
    % covariance of the first two: se of a sample covariance sqrt((s11 s22 + s12^2)/N)
    maplist([(A, B, _), P]>>(P is (A-1)*(B+1)), Ts, Ps),
    sum_list(Ps, SP),
    C12 is SP/20000,
    abs(C12 - 0.6) =< 5*sqrt((2*0.5 + 0.36)/20000),
    dist_mean(D, (1, -1, 0)).

test(indep_gaussians) :-
    D = indepGaussians([(0, 1), ([5, 6], [1, 0, 0, 4]), (-3, 0.25)]),
    dist_check(D),
    draws(D, 20000, 4, Ts),
    forall(member(T, Ts), T = (_, _, _, _)),
    maplist([(_, _, C, _), C]>>true, Ts, Cs),
    maplist([(_, _, _, E), E]>>true, Ts, Es),
    moments_ok(Cs, 6, 4),
    moments_ok(Es, -3, 0.25),
    dist_mean(D, (0, 5, 6, -3)).

test(dirichlet_on_the_simplex) :-
    draws(dirichlet([1, 2, 5]), 2000, 5, Ls),
    forall(member(L, Ls), ( length(L, 3), sum_list(L, S), abs(S-1) < 1.0e-12,
                            forall(member(X, L), X >= 0) )).

test(dirichlet_second_component) :-
    draws(dirichlet([1, 2, 5]), 20000, 5, Ls),
    maplist([[_, B, _], B]>>true, Ls, Bs),
    V is 2*6/(64*9),
    moments_ok(Bs, 0.25, V).

:- end_tests(ddc_dist_moments).

:- begin_tests(ddc_dist_density).

test(gaussian_example1) :-
    % example1 of the original system: density of g ~ gaussian(0, 0.01) at 0
    log_density(gaussian(0, 0.01), 0.0, LP),
    near(exp(LP), 3.98942280401433, 1.0e-12),
    log_density(gaussian(0, 0.02), 0.0, LP2),
    near(exp(LP2), 2.82094791773878, 1.0e-12).

test(gaussian_hand) :-
    log_density(gaussian(1, 4), 3, LP),
    near(LP, -0.5*log(2*pi*4) - 0.5).

test(poisson_hand) :-
    log_density(poisson(4), 4, LP),
    near(exp(LP), exp(-4)*4**4/24),
    log_density(poisson(4), 4.0, LP),
    log_density(poisson(4), -1, N1), ninf(N1),
    log_density(poisson(4), 2.5, N2), ninf(N2),
    log_density(poisson(0), 0, Z), Z =:= 0,
    log_density(poisson(0), 1, N3), ninf(N3).

test(beta_hand) :-
    log_density(beta(2, 3), 0.5, LP),
    near(exp(LP), 12*0.5*0.25),
    log_density(beta(1, 3), 0, L0), near(L0, log(3)),
    log_density(beta(2, 3), 0, N0), ninf(N0),
    log_density(beta(0.5, 2), 0, I), I =:= inf,
    log_density(beta(2, 3), 1.5, N1), ninf(N1).

test(gamma_hand) :-
    % gamma(2, scale 3) at 3: x e^(-x/3) / 9
    log_density(gamma(2, 3), 3, LP),
    near(exp(LP), 3*exp(-1)/9),
    log_density(gamma(1, 2), 0, L0), near(L0, log(0.5)),
    log_density(gamma(2, 3), -1, N), ninf(N).

test(invgamma_has_the_jacobian) :-
    % inverse gamma(3, scale 2) at 0.5: 2^3/Gamma(3) x^-4 e^(-2/x)
    log_density(invgamma(3, 2), 0.5, LP),
    near(exp(LP), 8/2 * 0.5**(-4) * exp(-4)),
    log_density(invgamma(3, 2), 0, N), ninf(N).

test(student_has_the_scale) :-
    % t(nu=1) is Cauchy: density at the mean 1/(pi*scale)
    log_density(student(1, 2, 9), 2, LP),
    near(exp(LP), 1/(pi*3)),
    log_density(student(1), 1, LP1),
    near(exp(LP1), 1/(2*pi)).

test(exponential_and_uniform_hand) :-
    log_density(exponential(2), 1, LP), near(LP, log(2) - 2),
    log_density(exponential(2), -0.1, N), ninf(N),
    log_density(contUniform(1, 5), 1, U1), near(U1, -log(4)),
    log_density(contUniform(1, 5), 5.01, N2), ninf(N2).

test(multivariate_gaussian_hand) :-
    % diagonal covariance: the product of the 1-D densities
    log_density(gaussian([0, 1], [1, 0, 0, 4]), (0.5, 2), LP),
    log_density(gaussian(0, 1), 0.5, A),
    log_density(gaussian(1, 4), 2, B),
    near(LP, A + B),
    log_density(gaussian([0, 1], [1, 0, 0, 4]), [0.5, 2], LP),
    log_density(gaussian([0, 1], [1, 0, 0, 4]), (0.5, 2, 3), N), ninf(N),
    log_density(gaussian([0, 1], [1, 0, 0, 4]), foo, N1), ninf(N1),
    log_density(gaussian([3], [4]), 3, L1), near(L1, -0.5*log(2*pi*4)).

test(correlated_gaussian_hand) :-
    % [[1,0.5],[0.5,1]]: det 0.75, inverse 1/0.75 [[1,-0.5],[-0.5,1]]
    log_density(gaussian([0, 0], [1, 0.5, 0.5, 1]), (1, 0), LP),
    near(LP, -log(2*pi) - 0.5*log(0.75) - 0.5*(1/0.75)).

test(indep_gaussians_hand) :-
    log_density(indepGaussians([(0, 1), (2, 4)]), (1, 2), LP),
    near(LP, -0.5*log(2*pi) - 0.5 - 0.5*log(2*pi*4)),
    log_density(indepGaussians([(0, 1)]), 1, L1),
    near(L1, -0.5*log(2*pi) - 0.5).

test(dirichlet_hand) :-
    % dirichlet([1,1,1]) is uniform on the simplex: density Gamma(3) = 2
    log_density(dirichlet([1, 1, 1]), [0.2, 0.3, 0.5], LP),
    near(LP, log(2)),
    log_density(dirichlet([1, 1, 1]), [0.2, 0.3, 0.6], N), ninf(N),
    log_density(dirichlet([1, 1, 1]), [-0.1, 0.6, 0.5], N2), ninf(N2).

test(finite_families) :-
    log_density(finite([0.2:1, 0.5:2, 0.3:1.0]), 1, L1), near(L1, log(0.5)),
    log_density(finite([0.2:a, 0.8:b]), c, N), ninf(N),
    log_density(finite([0.2:p(1), 0.8:p(2)]), p(1.0), L2), near(L2, log(0.2)),
    log_density(propfinite([1:a, 3:b]), b, L3), near(L3, log(0.75)),
    log_density(logfinite([0:a, 0:b]), a, L4), near(L4, log(0.5)),
    log_density(logfinite([-2.5:_]), anything, L5), near(L5, 0),
    log_density(uniform([a, b, a, c]), a, L6), near(L6, log(0.5)),
    log_density(uniform(1:4), 3, L7), near(L7, log(0.25)),
    log_density(uniform(1:4), 5, N7), ninf(N7),
    log_density(uniform((0, 0):(1, 2)), (1, 2), L8), near(L8, -log(6)),
    log_density(bool(0.3), true, L9), near(L9, log(0.3)),
    log_density(bool(1), false, N9), ninf(N9),
    log_density(val(3), 3.0, 0.0),
    log_density(val(3), 4, N10), ninf(N10).

% (Dist, Lo, Hi): a range holding all but a negligible part of the mass
integral_case(gaussian(1, 4), -19, 21).
integral_case(contUniform(-1, 3), -2, 4).
integral_case(beta(2, 3), 0, 1).
integral_case(beta(3, 1.5), 0, 1).
integral_case(gamma(2.5, 1.5), 0, 80).
integral_case(invgamma(3, 2), 0, 400).
integral_case(student(5, 1, 2), -600, 600).
integral_case(exponential(3), 0, 20).

test(density_integrates_to_one, [forall(integral_case(D, Lo, Hi))]) :-
    midpoint_integral(D, Lo, Hi, 40000, I),
    near(I, 1, 2.0e-3).

test(poisson_mass_sums_to_one) :-
    aggregate_all(sum(P), ( between(0, 100, K),
                            dist_log_density(poisson(7.5), K, LP), P is exp(LP) ), S),
    near(S, 1, 1.0e-12).

test(multivariate_density_integrates_to_one) :-
    % 2-D midpoint rule over +-8 standard deviations
    D = gaussian([0, 0], [1, 0.5, 0.5, 2]),
    N = 200, H is 16*sqrt(2)/N,
    N1 is N - 1,
    aggregate_all(sum(P),
                  ( between(0, N1, I), between(0, N1, J),
                    X is -8*sqrt(2) + (I + 0.5)*H,
                    Y is -8*sqrt(2) + (J + 0.5)*H,
                    dist_log_density(D, (X, Y), LP), P is exp(LP) ),
                  S),
    near(S*H*H, 1, 1.0e-3).

:- end_tests(ddc_dist_density).

:- begin_tests(ddc_dist_errors).

bad(gaussian(0, -1), negative_variance).
bad(gaussian(0, 0), not_positive(variance)).
bad(gaussian(a, 1), not_a_number(a)).
bad(gaussian(0, _), not_a_number(_)).
bad(gaussian(X, 1), not_a_number(_)) :- X is nan.
bad(gaussian(X, 1), not_finite(_)) :- X is inf.
bad(finite([0.5:a, 0.4:b]), probabilities_sum(_)).
bad(finite([1.2:a, -0.2:b]), negative_probability(-0.2)).
bad(finite([0.5:a, b]), malformed_entry(b)).
bad(finite(a), not_a_list(a)).
bad(finite([]), probabilities_sum(0)).
bad(propfinite([0:a, 0:b]), empty_support).
bad(propfinite([1:a, -1:b]), negative_weight(-1)).
bad(logfinite([-(inf):a]), empty_support).
bad(logfinite([x:a]), not_a_number(x)).
bad(uniform([]), empty_support).
bad(uniform(5:1), empty_support).
bad(uniform(1.5:3), not_integer(1.5)).
bad(uniform((0, 0):(1, 2, 3)), dimension_mismatch(bounds, 2, 3)).
bad(bool(1.5), probability_out_of_range(1.5)).
bad(bool(-0.1), probability_out_of_range(-0.1)).
bad(gaussian([0, 0], [1, 0, 0]), dimension_mismatch(covariance, 4, 3)).
bad(gaussian([0, 0], [1, 0.2, 0.3, 1]), not_symmetric).
bad(gaussian([0, 0], [1, 2, 2, 1]), not_positive_definite).
bad(gaussian([0, 0], [1, 0, 0, 0]), not_positive_definite).
bad(gaussian([], []), empty_support).
bad(indepGaussians([(0, -1)]), negative_variance).
bad(indepGaussians([foo]), malformed_block(foo)).
bad(indepGaussians([]), empty_support).
bad(contUniform(2, 1), empty_support).
bad(contUniform(1, 1), not_positive(width)).
bad(beta(0, 1), not_positive(alpha)).
bad(beta(1, -2), not_positive(beta)).
bad(gamma(-1, 1), not_positive(shape)).
bad(gamma(1, 0), not_positive(scale)).
bad(invgamma(0, 1), not_positive(shape)).
bad(student(0, 0, 1), not_positive(nu)).
bad(student(3, 0, -1), negative_variance).
bad(poisson(-1), negative(lambda)).
bad(exponential(0), not_positive(rate)).
bad(dirichlet([1, 0]), not_positive(alpha)).
bad(dirichlet([]), empty_support).
bad(foo(1), unknown_distribution).
bad(gaussian(1, 2, 3), unknown_distribution).
bad(_, unbound).

test(invalid, [forall(bad(D, Cause))]) :-
    catch(dist_check(D), error(ddc_distribution(D1, C), _), true),
    nonvar(C),
    D1 =@= D,
    subsumes_term(Cause, C).

test(valid, [forall(member(D, [finite([0.2:a, 0.8:b]), finite([0.1:a, 0.2:b, 0.7:c]),
                               propfinite([1:a]), logfinite([-(inf):a, 3:b]),
                               uniform([x]), uniform(3:3), bool(0), bool(1), val(_),
                               gaussian(0, 1), gaussian([1, 2], [2, 1, 1, 2]),
                               indepGaussians([(0, 1), ([1], [2])]), contUniform(0, 1),
                               beta(1, 1), gamma(1, 1), invgamma(1, 1), student(1),
                               student(1, 0, 1), poisson(0), exponential(1),
                               dirichlet([1])]))]) :-
    dist_check(D).

test(message_is_a_sentence) :-
    catch(dist_check(gaussian(0, -1)), E, true),
    message_text(E, S),
    once(sub_string(S, _, _, _, "gaussian(0,-1)")),
    once(sub_string(S, _, _, _, "variance is negative")),
    message_text(ddc_distribution(bool(2), probability_out_of_range(2)), S2),
    once(sub_string(S2, _, _, _, "not in [0,1]")).

message_text(Term, S) :-
    '$messages':translate_message(Term, Lines, []),
    with_output_to(string(S), print_message_lines(current_output, '', Lines)).

:- end_tests(ddc_dist_errors).

:- begin_tests(ddc_dist_api).

all_dists([ finite([0.2:1, 0.8:2]), propfinite([1:a, 2:b]), logfinite([0:a, -1:b]),
            uniform([a, b, c]), uniform(1:6), uniform((0, 0):(2, 2)), bool(0.4), val(v),
            gaussian(0, 1), gaussian([0, 0], [1, 0.3, 0.3, 1]), indepGaussians([(0, 1), (1, 1)]),
            contUniform(0, 1), beta(2, 2), gamma(0.5, 1), gamma(3, 1), invgamma(2, 1),
            student(3), student(3, 0, 2), poisson(2), poisson(30), exponential(1),
            dirichlet([1, 2]) ]).

test(reproducible) :-
    all_dists(Ds),
    forall(member(D, Ds),
           ( draws(D, 50, 123, A), draws(D, 50, 123, B), A == B,
             draws(D, 50, 124, C), ( dist_discrete(D) -> true ; A \== C ) )).

test(deterministic) :-
    all_dists(Ds),
    forall(member(D, Ds),
           ( call_cleanup(dist_sample(D, X), Det1 = true), Det1 == true,
             call_cleanup(dist_log_density(D, X, LP), Det2 = true), Det2 == true,
             number(LP) )).

test(steadfast) :-
    set_random(seed(1)),
    dist_sample(val(3), 3),
    \+ dist_sample(val(3), 4),
    dist_log_density(val(3), 3, 0.0).

test(discrete) :-
    forall(member(D, [finite([1:a]), propfinite([1:a]), logfinite([0:a]), uniform([a]),
                      uniform(1:2), bool(0.5), val(a), poisson(1)]),
           dist_discrete(D)),
    forall(member(D, [gaussian(0, 1), gaussian([0], [1]), indepGaussians([(0, 1)]),
                      contUniform(0, 1), beta(1, 1), gamma(1, 1), invgamma(1, 1),
                      student(1, 0, 1), exponential(1), dirichlet([1, 1])]),
           \+ dist_discrete(D)).

test(support) :-
    dist_support(finite([0.2:a, 0.5:b, 0.3:a]), [P1-a, 0.5-b]), near(P1, 0.5),
    dist_support(finite([0.5:1, 0.5:1.0]), [1.0-1]),
    dist_support(finite([0.5:a, 0.0:b, 0.5:c]), [0.5-a, 0.5-c]),
    dist_support(propfinite([1:a, 3:b]), [0.25-a, 0.75-b]),
    dist_support(logfinite([0:a, 0:b, -(inf):c]), [0.5-a, 0.5-b]),
    dist_support(uniform([x, y, x, z]), [0.5-x, 0.25-y, 0.25-z]),
    dist_support(uniform(2:4), [A-2, A-3, A-4]), near(A, 1/3),
    dist_support(uniform((0, 0):(1, 1)), [0.25-(0, 0), 0.25-(0, 1), 0.25-(1, 0), 0.25-(1, 1)]),
    dist_support(bool(0.25), [0.25-true, 0.75-false]),
    dist_support(val(q), [1.0-q]),
    \+ dist_support(gaussian(0, 1), _),
    \+ dist_support(poisson(1), _).

test(mean) :-
    dist_mean(finite([0.25:2, 0.75:4]), 3.5),
    \+ dist_mean(finite([0.25:a, 0.75:4]), _),
    \+ dist_mean(bool(0.5), _),
    dist_mean(val(2), 2),
    dist_mean(gaussian([1, 2], [1, 0, 0, 1]), (1, 2)),
    dist_mean(gaussian([1], [1]), 1),
    dist_mean(dirichlet([1, 3]), [0.25, 0.75]),
    dist_mean(gamma(2, 3), 6),
    \+ dist_mean(invgamma(1, 1), _),
    \+ dist_mean(student(1), _),
    dist_mean(poisson(4), 4),
    dist_mean(uniform(1:4), 2.5).

test(finite_rounding_never_fails) :-
    % probabilities summing to just below 1 (within the 1e-9 tolerance)
    D = finite([0.3333333333:a, 0.3333333333:b, 0.3333333333:c]),
    dist_check(D),
    draws(D, 2000, 17, Xs),
    length(Xs, 2000).

test(one_dimensional_multivariate_value_is_a_number) :-
    set_random(seed(2)),
    dist_sample(gaussian([5], [1]), X), number(X),
    dist_sample(indepGaussians([(5, 1)]), Y), number(Y),
    dist_sample(gaussian([0, 0], [1, 0, 0, 1]), (A, B)), number(A), number(B).

%   Prepared distributions (the batched filter's): the same draws and
%   densities as the distribution itself, the mean bound or passed.
test(prepared_gaussians_draw_and_weigh_as_the_distribution) :-
    Cov = [0.04, 0.01, 0.0, 0.01, 0.09, 0.02, 0.0, 0.02, 0.16],
    forall(member(D-Slots-Mean-X,
                  [ gaussian([A, B, C], Cov)-(A, B, C)-(0.1, -0.2, 0.3)-(0.15, -0.1, 0.2),
                    gaussian(M, 0.25)-M-1.5-1.2 ]),
           (   dist_prepare(D, P),
               P \= any(_),
               dist_mean_slots(P, S), S == Slots,
               copy_term(D-Slots, D1-Mean),
               set_random(seed(7)), dist_sample(D1, X1),
               set_random(seed(7)), dist_sample_at(P, Mean, X2),
               X1 == X2,
               copy_term(P-Slots, P1-Mean),
               set_random(seed(7)), dist_sample_prepared(P1, X3),
               X3 == X1,
               dist_log_density(D1, X, L1),
               dist_log_density_at(P, Mean, X, L2),
               dist_log_density_prepared(P1, X, L3),
               abs(L1 - L2) < 1.0e-12, abs(L1 - L3) < 1.0e-12
           )).

test(other_distributions_are_kept_and_checked_at_each_use) :-
    dist_prepare(uniform(L), P),
    P == any(uniform(L)),
    \+ dist_mean_slots(P, _),
    L = [a, b],
    set_random(seed(3)), dist_sample(uniform([a, b]), X1),
    set_random(seed(3)), dist_sample_prepared(P, X2),
    X1 == X2,
    catch(dist_sample_prepared(any(gaussian(0.0, -1.0)), _), E, true),
    E = error(ddc_distribution(_, negative_variance), _).

test(a_prepared_covariance_is_checked_once) :-
    catch(dist_prepare(gaussian([_, _, _], [1, 0, 0, 0, -1, 0, 0, 0, 1]), _), E, true),
    E = error(ddc_distribution(_, _), _).

:- end_tests(ddc_dist_api).

%   Optimal proposals against a Kalman update computed by hand:
%   prior x ~ N([1,2], [[2,0.5],[0.5,1]]), H = I, R = I, y = [3,1]:
%   S = [[3,0.5],[0.5,2]], det S = 5.75, S^-1 = [[2,-0.5],[-0.5,3]]/5.75,
%   K = P S^-1 = [[3.75,0.5],[0.5,2.75]]/5.75, y - Hx = [2,-1],
%   M' = [1 + 7/5.75, 2 - 1.75/5.75] = [2.2173913, 1.6956522],
%   P' = P - K P = [[0.6521739,0.0869565],
%   [0.0869565,0.4782609]], (y-Hx)' S^-1 (y-Hx) = 13/5.75,
%   log w = -1/2 (13/5.75 + log 5.75 + 2 log 2 pi) = -3.8429118.
kalman_block_2d(([1,2],[2,0.5,0.5,1],[1,0,0,1],[1,0,0,1],[3,1])).

close_lists(Xs, Ys, Tol) :-
    maplist([X, Y]>>(abs(X-Y) =< Tol), Xs, Ys).

:- begin_tests(ddc_dist_kalman).

test(log_weight_and_posterior_density_are_the_hand_computed_ones) :-
    kalman_block_2d(B),
    D = logIndepOptimalProposals([B]),
    dist_check(D),
    set_random(seed(3)),
    dist_sample(D, [(X1, X2), LogW]),
    assertion(abs(LogW - -3.8429118) < 1.0e-6),
    dist_log_density(D, [(X1, X2), LogW], LP),
    dist_log_density(gaussian([2.2173913, 1.6956522],
                              [0.6521739, 0.0869565, 0.0869565, 0.4782609]), (X1, X2), LP0),
    assertion(abs(LP - LP0) < 1.0e-5),
    LW1 is LogW + 0.5,
    dist_log_density(D, [(X1, X2), LW1], LPBad),
    assertion(LPBad =:= -inf).

test(optimal_proposal_samples_have_the_posterior_moments) :-
    kalman_block_2d((M, P, H, R, Y)),
    draws(optimalProposal(M, P, H, R, Y), 4000, 11, Ts),
    maplist([(A, B), A, B]>>true, Ts, As, Bs),
    moments_ok(As, 2.2173913, 0.6521739),
    moments_ok(Bs, 1.6956522, 0.4782609).

test(independent_blocks_one_dimensional_measurement) :-
    %   tracking.pl's block: ([0.6,0], diag(0.0002,1e-7)), H = [1,0],
    %   R = 0.001, y = 0.7: gain 0.0002/0.0012 = 1/6, mean 0.6 + 0.1/6,
    %   variance 0.0002*5/6; log w = log N(0.7; 0.6, 0.0012)
    B = ([0.6,0],[0.0002,0,0,1.0e-7],[1,0],[0.001],[0.7]),
    D = indepOptimalProposals([B, B]),
    dist_check(D),
    draws(D, 4000, 5, Ts),
    maplist([(A, _, C, _), A, C]>>true, Ts, As, Cs),
    moments_ok(As, 0.6166667, 0.00016666667),
    moments_ok(Cs, 0.6166667, 0.00016666667),
    dist_sample(logIndepOptimalProposals([B, B]), [_, LogW]),
    Exact is 2*(-0.5*(0.01/0.0012 + log(0.0012) + log(2*pi))),
    assertion(abs(LogW - Exact) < 1.0e-9).

test(logweight_weighs_any_value_by_its_log_mass_and_cannot_be_sampled) :-
    dist_check(logweight([-2.5])),
    dist_log_density(logweight([-2.5]), anything, LP),
    assertion(LP =:= -2.5),
    dist_log_density(logweight(-1), _, LP1),
    assertion(LP1 =:= -1.0),
    catch(dist_sample(logweight(0.0), _), error(ddc_distribution(_, no_sampler), _), true).

test(a_malformed_block_is_an_error, [throws(error(ddc_distribution(_, dimension_mismatch(measurement_matrix, 2, 3)), _))]) :-
    dist_check(indepOptimalProposals([([0.6,0],[0.0002,0,0,1.0e-7],[1,0,0],[0.001],[0.7])])).

test(a_singular_innovation_is_an_error, [throws(error(ddc_distribution(_, singular_innovation), _))]) :-
    dist_check(optimalProposal([0.0],[0.0],[1],[0.0],[1.0])).

:- end_tests(ddc_dist_kalman).
