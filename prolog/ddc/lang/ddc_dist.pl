/*  ddc_dist.pl -- the probability distributions of the DDC system.

    Every distribution of the Distributional Clauses language has here a
    parameter check, a sampler that uses only SWI-Prolog's own random
    generator (so set_random(seed(S)) reproduces every draw bit for bit),
    an exact log density (continuous) or log mass (discrete), and where
    they exist its finite support and its mean.

    The module keeps no state of its own.  Hot predicates (dist_sample/2,
    dist_log_density/3) are indexed on the functor of the distribution
    term, build no intermediate lists for 1-D distributions and raise no
    exceptions on valid input.

    Arithmetic note: SWI-Prolog raises float_overflow for arithmetic on
    infinite floats (e.g. X is -inf + 1.0).  The log densities returned
    here may be the float -inf (a value outside the support); callers that
    add log weights must test for it before doing arithmetic.
*/

:- module(ddc_dist,
          [ dist_check/1,               % +Dist
            dist_sample/2,              % +Dist, -Value
            dist_log_density/3,         % +Dist, +Value, -LogP
            dist_discrete/1,            % +Dist
            dist_support/2,             % +Dist, -Pairs
            dist_mean/2,                % +Dist, -Mean
            dist_prepare/2,             % +Dist, -Prepared
            dist_sample_prepared/2,     % +Prepared, -Value
            dist_log_density_prepared/3,% +Prepared, +Value, -LogP
            dist_mean_slots/2,          % +Prepared, -MeanSlots
            dist_sample_at/3,           % +Prepared, +Mean, -Value
            dist_log_density_at/4,      % +Prepared, +Mean, +Value, -LogP
            dist_prepared_factor/3      % +Prepared, -Factor, -LogNorm
          ]).
%   Arithmetic compiled inline (local to this file; see ddc.pl).
:- set_prolog_flag(optimise, true).

:- use_module(library(lists)).
:- use_module(library(apply)).

/** <module> Distributions of the DDC system

Term forms (parameters are evaluated numbers; integers are accepted
wherever a float is):

| Term | Kind | Value |
|---|---|---|
| finite([P:V,...]) | discrete, P >= 0 summing to 1 (within 1e-9) | one of the V |
| propfinite([W:V,...]) | discrete, weights W >= 0 normalised by their sum | one of the V |
| logfinite([L:V,...]) | discrete, log weights, normalised (softmax) | one of the V |
| uniform(List) | discrete, uniform over the list positions | an element |
| uniform(A:C) | discrete, integers A..C inclusive; with tuples of integers, the grid | integer / tuple |
| bool(P) | discrete, P(true) = P | true or false |
| val(V) | point mass | V |
| gaussian(M, Var) | 1-D normal, second argument the VARIANCE | float |
| gaussian(Ms, CovFlat) | k-D normal, covariance row-major k*k | (X1,...,Xk); a float when k = 1 |
| indepGaussians([(M,V),...]) | independent blocks, each (Number,Variance) or (MeanList,CovFlat) | concatenated tuple |
| optimalProposal(M, P, H, R, Y) | Kalman posterior of x ~ N(M,P) given Y = H x + N(0,R) | tuple (float when 1-D) |
| indepOptimalProposals([(M,P,H,R,Y),...]) | independent blocks, each such a posterior | concatenated tuple |
| logIndepOptimalProposals([(M,P,H,R,Y),...]) | the same, with the log predictive density of the Ys | [Tuple, LogW] |
| logweight(W) | weight only: log mass W at every value (no sampler) | - |
| contUniform(A, B) | uniform on [A,B] | float |
| beta(Alpha, Beta) | beta | float in [0,1] |
| gamma(Shape, Scale) | gamma with SCALE (mean Shape*Scale) | float >= 0 |
| invgamma(Shape, Scale) | inverse gamma: 1/X for X ~ gamma(Shape, 1/Scale) | float > 0 |
| student(Nu, Mean, Var) | location-scale t: Mean + sqrt(Var)*T, T ~ t(Nu) | float |
| student(Nu) | standard t | float |
| poisson(Lambda) | Poisson, Lambda >= 0 | integer >= 0 |
| exponential(Rate) | exponential with RATE (mean 1/Rate) | float >= 0 |
| dirichlet(Alphas) | Dirichlet | list of floats summing to 1 |

Matching a value against the entries of a discrete distribution: numbers
compare by value (1 matches 1.0), other terms structurally with the same
rule inside compounds; an unbound entry (as in logfinite([W:_])) matches
any value.  Entries with equal values add up.

Differences from the original DC system (all deliberate):
  - invgamma: the original weighted with the gamma density of 1/x and
    omitted the Jacobian 1/x^2; here the density is the inverse-gamma one,
    Scale^Shape/Gamma(Shape) * x^(-Shape-1) * exp(-Scale/x).
  - student(Nu,Mean,Var): the original omitted the 1/sqrt(Var) factor of
    the location-scale density; it is included here.  Var is the squared
    scale, not the variance of the distribution (which is Var*Nu/(Nu-2)).
  - logfinite: the original static engine gave weight 0 and its particle
    filter used the unnormalised log weight of the matching entry; here
    the log mass is normalised (log-sum-exp over matching entries minus
    log-sum-exp over all entries), so logfinite([W:_]) has log mass 0.
  - finite: a sample never fails; when rounding leaves the uniform draw
    above the cumulative sum the last entry of positive probability is
    returned.
  - every distribution has a density; none silently weighs 0.
  - logweight(W) is this engine's form of the original's one-entry
    logfinite([W:_]) observation weight: dc_compat_load.pl rewrites the
    latter to the former in programs written for the original.

Optimal proposals (the original's sampling.pl; Doucet et al. 2000): a
block (M, P, H, R, Y) is a prior x ~ N(M, P) (M a list of k means, P the
k*k covariance row-major), a measurement matrix H (m*k row-major), a
measurement noise covariance R (m*m) and the measurement Y (a list of m,
or a number when m = 1).  The Kalman update is

    S  = H P H' + R                     (innovation covariance)
    K  = P H' S^-1                      (gain)
    M' = M + K (Y - H M)                (posterior mean)
    P' = P - K H P                      (posterior covariance)
    log w = log N(Y; H M, S)
          = -1/2 ((Y-HM)' S^-1 (Y-HM) + log det S + m log 2 pi)

optimalProposal and indepOptimalProposals draw x from N(M', P') (per
block); logIndepOptimalProposals draws [X, LogW] with LogW the sum of the
blocks' log w, the predictive density that weighs the particle (the
original's tracking example reads it into logfinite([LogW:_])).
*/

:- multifile
    prolog:message//1,
    prolog:error_message//1.

%!  dist_check(+Dist) is det.
%
%   True if Dist is a known distribution with valid parameters.
%   Otherwise throws error(ddc_distribution(Dist, Cause), _), where Cause
%   is one of: unbound, unknown_distribution, not_a_number(X),
%   not_finite(X), not_a_list(X), malformed_entry(E),
%   negative_probability(P), probabilities_sum(S), negative_weight(W),
%   empty_support, not_integer(X), probability_out_of_range(P),
%   negative_variance, not_positive(Param), negative(Param),
%   dimension_mismatch(What, Expected, Found), not_symmetric,
%   not_positive_definite, malformed_block(B).  Param names the
%   parameter (variance, shape, scale, rate, nu, alpha, beta, width,
%   lambda).

dist_check(Dist) :-
    var(Dist), !,
    dist_error(Dist, unbound).
dist_check(Dist) :-
    check(Dist), !.
dist_check(Dist) :-
    dist_error(Dist, unknown_distribution).

dist_error(Dist, Cause) :-
    throw(error(ddc_distribution(Dist, Cause), _)).

check(finite(Ps)) :-
    D = finite(Ps),
    must_list(D, Ps),
    check_entries(Ps, D, prob, 0, S),
    (   abs(S - 1) =< 1.0e-9
    ->  true
    ;   dist_error(D, probabilities_sum(S))
    ).
check(propfinite(Ws)) :-
    D = propfinite(Ws),
    must_list(D, Ws),
    check_entries(Ws, D, weight, 0, S),
    (   S > 0 -> true ; dist_error(D, empty_support) ).
check(logfinite(Ls)) :-
    D = logfinite(Ls),
    must_list(D, Ls),
    check_log_entries(Ls, D, false, AnyFinite),
    (   AnyFinite == true -> true ; dist_error(D, empty_support) ).
check(uniform(Spec)) :-
    check_uniform(Spec, uniform(Spec)).
check(bool(P)) :-
    D = bool(P),
    must_number(D, P),
    (   P >= 0, P =< 1 -> true ; dist_error(D, probability_out_of_range(P)) ).
check(val(_)).
check(gaussian(M, C)) :-
    D = gaussian(M, C),
    (   is_list(M)
    ->  check_mv_gaussian(D, M, C, _)
    ;   must_number(D, M),
        must_number(D, C),
        (   C < 0 -> dist_error(D, negative_variance)
        ;   C =:= 0 -> dist_error(D, not_positive(variance))
        ;   true
        )
    ).
check(indepGaussians(Bs)) :-
    D = indepGaussians(Bs),
    must_list(D, Bs),
    (   Bs == [] -> dist_error(D, empty_support) ; true ),
    forall(member(B, Bs), check_block(D, B)).
check(optimalProposal(M, P, H, R, Y)) :-
    D = optimalProposal(M, P, H, R, Y),
    kalman_block(D, (M, P, H, R, Y), _, _).
check(indepOptimalProposals(Bs)) :-
    D = indepOptimalProposals(Bs),
    kalman_blocks(D, Bs, _, _).
check(logIndepOptimalProposals(Bs)) :-
    D = logIndepOptimalProposals(Bs),
    kalman_blocks(D, Bs, _, _).
check(logweight(W)) :-
    D = logweight(W),
    logweight_value(D, W, _).
check(contUniform(A, B)) :-
    D = contUniform(A, B),
    must_number(D, A),
    must_number(D, B),
    (   B < A -> dist_error(D, empty_support)
    ;   B =:= A -> dist_error(D, not_positive(width))
    ;   true
    ).
check(beta(A, B)) :-
    D = beta(A, B),
    must_positive(D, alpha, A),
    must_positive(D, beta, B).
check(gamma(K, S)) :-
    D = gamma(K, S),
    must_positive(D, shape, K),
    must_positive(D, scale, S).
check(invgamma(K, S)) :-
    D = invgamma(K, S),
    must_positive(D, shape, K),
    must_positive(D, scale, S).
check(student(Nu)) :-
    must_positive(student(Nu), nu, Nu).
check(student(Nu, M, V)) :-
    D = student(Nu, M, V),
    must_positive(D, nu, Nu),
    must_number(D, M),
    must_number(D, V),
    (   V < 0 -> dist_error(D, negative_variance)
    ;   V =:= 0 -> dist_error(D, not_positive(variance))
    ;   true
    ).
check(poisson(L)) :-
    D = poisson(L),
    must_number(D, L),
    (   L < 0 -> dist_error(D, negative(lambda)) ; true ).
check(exponential(R)) :-
    must_positive(exponential(R), rate, R).
check(dirichlet(As)) :-
    D = dirichlet(As),
    must_list(D, As),
    (   As == [] -> dist_error(D, empty_support) ; true ),
    forall(member(A, As), must_positive(D, alpha, A)).

must_list(D, L) :-
    (   is_list(L) -> true ; dist_error(D, not_a_list(L)) ).

must_number(D, X) :-
    (   number(X)
    ->  (   float(X), X =\= X
        ->  dist_error(D, not_a_number(X))
        ;   float(X), abs(X) > 1.0e308
        ->  dist_error(D, not_finite(X))
        ;   true
        )
    ;   dist_error(D, not_a_number(X))
    ).

must_positive(D, Name, X) :-
    must_number(D, X),
    (   X > 0 -> true ; dist_error(D, not_positive(Name)) ).

must_integer(D, X) :-
    (   integer(X) -> true ; dist_error(D, not_integer(X)) ).

check_entries([], _, _, S, S).
check_entries([E|Es], D, Kind, S0, S) :-
    (   nonvar(E), E = P:_
    ->  true
    ;   dist_error(D, malformed_entry(E))
    ),
    must_number(D, P),
    (   P >= 0
    ->  true
    ;   Kind == prob
    ->  dist_error(D, negative_probability(P))
    ;   dist_error(D, negative_weight(P))
    ),
    S1 is S0 + P,
    check_entries(Es, D, Kind, S1, S).

check_log_entries([], _, Any, Any).
check_log_entries([E|Es], D, Any0, Any) :-
    (   nonvar(E), E = L:_
    ->  true
    ;   dist_error(D, malformed_entry(E))
    ),
    (   ( L == -(inf) ; number(L), L =:= -inf )   % log of weight 0
    ->  Any1 = Any0
    ;   must_number(D, L),
        Any1 = true
    ),
    check_log_entries(Es, D, Any1, Any).

check_uniform(Spec, D) :-
    var(Spec), !,
    dist_error(D, not_a_list(Spec)).
check_uniform(A:C, D) :- !,
    (   number(A), number(C)
    ->  must_integer(D, A),
        must_integer(D, C),
        (   C < A -> dist_error(D, empty_support) ; true )
    ;   tuple_list(A, As),
        tuple_list(C, Cs),
        length(As, N),
        (   length(Cs, N) -> true
        ;   length(Cs, NC), dist_error(D, dimension_mismatch(bounds, N, NC))
        ),
        forall(member(X, As), must_integer(D, X)),
        forall(member(X, Cs), must_integer(D, X)),
        (   maplist(=<, As, Cs) -> true ; dist_error(D, empty_support) )
    ).
check_uniform(L, D) :-
    must_list(D, L),
    (   L == [] -> dist_error(D, empty_support) ; true ).

check_block(D, B) :-
    (   nonvar(B), B = (M, C)
    ->  (   is_list(M)
        ->  check_mv_gaussian(D, M, C, _)
        ;   must_number(D, M),
            must_number(D, C),
            (   C < 0 -> dist_error(D, negative_variance)
            ;   C =:= 0 -> dist_error(D, not_positive(variance))
            ;   true
            )
        )
    ;   dist_error(D, malformed_block(B))
    ).

check_mv_gaussian(D, Ms, Cs, L) :-
    must_list(D, Cs),
    (   Ms == [] -> dist_error(D, empty_support) ; true ),
    forall(member(X, Ms), must_number(D, X)),
    forall(member(X, Cs), must_number(D, X)),
    length(Ms, K),
    length(Cs, NC),
    K2 is K*K,
    (   NC =:= K2 -> true ; dist_error(D, dimension_mismatch(covariance, K2, NC)) ),
    CT =.. [c|Cs],
    (   symmetric(K, CT) -> true ; dist_error(D, not_symmetric) ),
    (   cholesky(K, CT, L) -> true ; dist_error(D, not_positive_definite) ).

symmetric(K, CT) :-
    K1 is K - 1,
    forall(( between(0, K1, I), between(0, K1, J), J > I ),
           ( cov(K, CT, I, J, A), cov(K, CT, J, I, B),
             abs(A-B) =< 1.0e-9*(1+abs(A)+abs(B)) )).

		 /*******************************
		 *            SAMPLING          *
		 *******************************/

%!  dist_sample(+Dist, -Value) is det.
%
%   Draw one Value from Dist using only SWI-Prolog's random generator
%   (random_float and random/1), so set_random(seed(S)) makes the draws
%   reproducible.  Assumes dist_check(Dist) holds.  Samplers: inverse CDF
%   walks for the finite families, Box-Muller for gaussians, Cholesky for
%   multivariate gaussians, Marsaglia-Tsang for gamma (with the U^(1/k)
%   boost for shape < 1) and everything built on it (beta, invgamma,
%   student, dirichlet), inversion for poisson(Lambda < 10) and Hoermann's
%   PTRS transformed rejection for Lambda >= 10.

dist_sample(finite(Ps), X) :-
    U is random_float,
    finite_pick(Ps, U, Ps, X).
dist_sample(propfinite(Ws), X) :-
    sum_weights(Ws, 0, S),
    U is random_float*S,
    finite_pick(Ws, U, Ws, X).
dist_sample(logfinite(Ls), X) :-
    NInf is -inf, max_log(Ls, NInf, Max),
    sum_exp(Ls, Max, 0.0, S),
    U is random_float*S,
    logfinite_pick(Ls, Max, U, Ls, X).
dist_sample(uniform(Spec), X) :-
    uniform_sample(Spec, X).
dist_sample(bool(P), X) :-
    (   random_float < P -> X = true ; X = false ).
dist_sample(val(V), V).
dist_sample(gaussian(M, V), X) :-
    (   number(M)
    ->  std_normal(Z),
        X is M + sqrt(V)*Z
    ;   mv_sample(M, V, X)
    ).
dist_sample(indepGaussians(Bs), X) :-
    blocks_sample(Bs, Xs),
    list_value(Xs, X).
dist_sample(optimalProposal(M, P, H, R, Y), X) :-
    kalman_blocks(optimalProposal, [(M, P, H, R, Y)], Post, _),
    dist_sample(indepGaussians(Post), X).
dist_sample(indepOptimalProposals(Bs), X) :-
    kalman_blocks(indepOptimalProposals, Bs, Post, _),
    dist_sample(indepGaussians(Post), X).
dist_sample(logIndepOptimalProposals(Bs), [X, LogW]) :-
    kalman_blocks(logIndepOptimalProposals, Bs, Post, LogW),
    dist_sample(indepGaussians(Post), X).
dist_sample(logweight(W), _) :-
    dist_error(logweight(W), no_sampler).
dist_sample(contUniform(A, B), X) :-
    X is A + (B-A)*random_float.
dist_sample(beta(A, B), X) :-
    beta_sample(A, B, X).
dist_sample(gamma(K, S), X) :-
    std_gamma(K, G),
    X is G*S.
dist_sample(invgamma(K, S), X) :-
    positive_std_gamma(K, G),
    X is S/G.
dist_sample(student(Nu), X) :-
    std_t(Nu, X).
dist_sample(student(Nu, M, V), X) :-
    std_t(Nu, T),
    X is M + sqrt(V)*T.
dist_sample(poisson(L), X) :-
    (   L < 10
    ->  U is random_float,
        P0 is exp(-L),
        poisson_walk(0, P0, P0, U, L, X)
    ;   poisson_ptrs(L, X)
    ).
dist_sample(exponential(R), X) :-
    X is -log(random_float)/R.
dist_sample(dirichlet(As), X) :-
    dirichlet_sample(As, X).

% finite_pick(+Entries, +U, +All, -X): walk the cumulative weights.
finite_pick([P:V|T], U, All, X) :-
    (   U < P
    ->  X = V
    ;   T == []
    ->  last_positive(All, X)
    ;   U1 is U - P,
        finite_pick(T, U1, All, X)
    ).

last_positive(All, X) :-
    reverse(All, R),
    member(P:V, R),
    P > 0, !,
    X = V.

sum_weights([], S, S).
sum_weights([W:_|T], S0, S) :-
    S1 is S0 + W,
    sum_weights(T, S1, S).

max_log([], M, M).
max_log([L:_|T], M0, M) :-
    (   L > M0 -> max_log(T, L, M) ; max_log(T, M0, M) ).

sum_exp([], _, S, S).
sum_exp([L:_|T], Max, S0, S) :-
    lexp(L, Max, W),
    S1 is S0 + W,
    sum_exp(T, Max, S1, S).

lexp(L, Max, W) :-
    (   L < -1.0e308 -> W = 0.0 ; W is exp(L - Max) ).

logfinite_pick([L:V|T], Max, U, All, X) :-
    lexp(L, Max, W),
    (   U < W
    ->  X = V
    ;   T == []
    ->  reverse(All, R),
        member(L1:V1, R), L1 > -1.0e308, !,
        X = V1
    ;   U1 is U - W,
        logfinite_pick(T, Max, U1, All, X)
    ).

uniform_sample(A:C, X) :- !,
    (   integer(A)
    ->  X is A + random(C - A + 1)
    ;   tuple_list(A, As),
        tuple_list(C, Cs),
        maplist(int_draw, As, Cs, Xs),
        list_value(Xs, X)
    ).
uniform_sample(List, X) :-
    length(List, N),
    I is random(N),
    list_pick(I, List, X0),
    X = X0.

%   list_pick(+I, +List, -X): X is the I-th (0-based) element, I valid.
list_pick(0, [X|_], X) :- !.
list_pick(I, [_|T], X) :-
    I1 is I - 1,
    list_pick(I1, T, X).

int_draw(A, C, X) :-
    X is A + random(C - A + 1).

%   std_normal(-Z): Box-Muller (one of the two outputs).
std_normal(Z) :-
    U1 is random_float,
    U2 is random_float,
    Z is sqrt(-2.0*log(U1))*cos(2.0*pi*U2).

%   std_normals(+K, -Zs): K standard normals, two per Box-Muller pair.
std_normals(0, []) :- !.
std_normals(1, [Z]) :- !,
    std_normal(Z).
std_normals(K, [Z1,Z2|Zs]) :-
    U1 is random_float,
    U2 is random_float,
    R is sqrt(-2.0*log(U1)),
    T is 2.0*pi*U2,
    Z1 is R*cos(T),
    Z2 is R*sin(T),
    K2 is K - 2,
    std_normals(K2, Zs).

%   std_gamma(+K, -G): G ~ gamma(K, scale 1), Marsaglia-Tsang.
std_gamma(K, G) :-
    (   K >= 1
    ->  D is K - 1/3,
        C is 1/sqrt(9*D),
        mt_gamma(D, C, G)
    ;   D is K + 2/3,                   % boost: gamma(K+1) * U^(1/K)
        C is 1/sqrt(9*D),
        mt_gamma(D, C, G1),
        U is random_float,
        G is G1*U**(1/K)
    ).

mt_gamma(D, C, G) :-
    std_normal(Z),
    V0 is 1 + C*Z,
    (   V0 =< 0
    ->  mt_gamma(D, C, G)
    ;   V is V0*V0*V0,
        U is random_float,
        Z2 is Z*Z,
        (   U < 1 - 0.0331*Z2*Z2
        ->  G is D*V
        ;   log(U) < 0.5*Z2 + D*(1 - V + log(V))
        ->  G is D*V
        ;   mt_gamma(D, C, G)
        )
    ).

positive_std_gamma(K, G) :-
    std_gamma(K, G0),
    (   G0 > 0 -> G = G0 ; positive_std_gamma(K, G) ).

beta_sample(A, B, X) :-
    std_gamma(A, G1),
    std_gamma(B, G2),
    S is G1 + G2,
    (   S > 0 -> X is G1/S ; beta_sample(A, B, X) ).

std_t(Nu, T) :-
    std_normal(Z),
    H is Nu/2,
    positive_std_gamma(H, G),
    T is Z/sqrt(2*G/Nu).

dirichlet_sample(As, X) :-
    gammas(As, Gs, 0, S),
    (   S > 0
    ->  divide_all(Gs, S, X)
    ;   dirichlet_sample(As, X)
    ).

gammas([], [], S, S).
gammas([A|As], [G|Gs], S0, S) :-
    std_gamma(A, G),
    S1 is S0 + G,
    gammas(As, Gs, S1, S).

divide_all([], _, []).
divide_all([G|Gs], S, [X|Xs]) :-
    X is G/S,
    divide_all(Gs, S, Xs).

poisson_walk(K0, P, F, U, L, K) :-
    (   U < F
    ->  K = K0
    ;   K1 is K0 + 1,
        P1 is P*L/K1,
        (   P1 =:= 0                    % the tail underflowed: stop
        ->  K = K1
        ;   F1 is F + P1,
            poisson_walk(K1, P1, F1, U, L, K)
        )
    ).

%   Hoermann (1993), "The transformed rejection method for generating
%   Poisson random variables", algorithm PTRS; for Lambda >= 10.
poisson_ptrs(L, K) :-
    SL is sqrt(L),
    LogL is log(L),
    B is 0.931 + 2.53*SL,
    A is -0.059 + 0.02483*B,
    InvAlpha is 1.1239 + 1.1328/(B - 3.4),
    VR is 0.9277 - 3.6224/(B - 2),
    ptrs_loop(L, LogL, A, B, InvAlpha, VR, K).

ptrs_loop(L, LogL, A, B, InvAlpha, VR, K) :-
    U is random_float - 0.5,
    V is random_float,
    US is 0.5 - abs(U),
    K0 is floor((2*A/US + B)*U + L + 0.43),
    (   US >= 0.07, V =< VR
    ->  K = K0
    ;   ( K0 < 0 ; US < 0.013, V > US )
    ->  ptrs_loop(L, LogL, A, B, InvAlpha, VR, K)
    ;   log(V) + log(InvAlpha) - log(A/(US*US) + B)
            =< -L + K0*LogL - lgamma(K0 + 1)
    ->  K = K0
    ;   ptrs_loop(L, LogL, A, B, InvAlpha, VR, K)
    ).

mv_sample(Ms, Cs, X) :-
    mv_draw(Ms, Cs, Xs),
    list_value(Xs, X).

%   mv_draw(+Means, +CovFlat, -Xs): one multivariate normal draw as a
%   list, X = M + L*Z with L the Cholesky factor; closed forms for the
%   dimensions 2 and 3 (which read the lower triangle, like cholesky/3).
mv_draw([M1, M2], [C11, _, C21, C22], Xs) :- !,
    L11 is sqrt(C11),
    L21 is C21/L11,
    L22 is sqrt(C22 - L21*L21),
    std_normals(2, [Z1, Z2]),
    X1 is M1 + L11*Z1,
    X2 is M2 + L21*Z1 + L22*Z2,
    Xs = [X1, X2].
mv_draw([M1, M2, M3], [C11, _, _, C21, C22, _, C31, C32, C33], Xs) :- !,
    chol3(C11, C21, C22, C31, C32, C33, L11, L21, L22, L31, L32, L33),
    std_normals(3, [Z1, Z2, Z3]),
    X1 is M1 + L11*Z1,
    X2 is M2 + L21*Z1 + L22*Z2,
    X3 is M3 + L31*Z1 + L32*Z2 + L33*Z3,
    Xs = [X1, X2, X3].
mv_draw(Ms, Cs, Xs) :-
    length(Ms, K),
    CT =.. [c|Cs],
    cholesky(K, CT, Rows),
    std_normals(K, Zs),
    affine(Rows, Ms, Zs, Xs).

chol3(C11, C21, C22, C31, C32, C33, L11, L21, L22, L31, L32, L33) :-
    L11 is sqrt(C11),
    L21 is C21/L11,
    L31 is C31/L11,
    L22 is sqrt(C22 - L21*L21),
    L32 is (C32 - L31*L21)/L22,
    L33 is sqrt(C33 - L31*L31 - L32*L32).

% affine(+LRows, +Means, +Zs, -Xs): X_i = M_i + sum_p L_ip Z_p.
affine([], [], _, []).
affine([Row|Rows], [M|Ms], Zs, [X|Xs]) :-
    dot(Row, Zs, 0, S),
    X is M + S,
    affine(Rows, Ms, Zs, Xs).

blocks_sample([], []).
blocks_sample([(M, C)|Bs], Xs) :-
    (   number(M)
    ->  std_normal(Z),
        X is M + sqrt(C)*Z,
        Xs = [X|Xs1]
    ;   mv_draw(M, C, Ys),
        append(Ys, Xs1, Xs)
    ),
    blocks_sample(Bs, Xs1).

		 /*******************************
		 *     PREPARED DISTRIBUTIONS   *
		 *******************************/

%!  dist_prepare(+Dist, -Prepared) is det.
%
%   Prepared is Dist with what does not depend on its mean worked out once:
%   for many draws or densities of distributions that differ only in the
%   mean (the batched filter: one distribution term for a batch of
%   particles, the mean bound per particle).  The mean of a gaussian may
%   hold unbound variables, shared with Prepared: bind them, then call
%   dist_sample_prepared/2 or dist_log_density_prepared/3 (which give what
%   dist_sample/2 and dist_log_density/3 give for the bound Dist, with the
%   same random draws).  A 1-D gaussian with a numeric variance and a 3-D
%   one with a ground covariance are prepared (the variance's root, the
%   covariance's Cholesky factor and the log normaliser are computed here,
%   once, when dist_check/1 accepts them); any other Dist is kept as it is
%   and checked at each use.
dist_prepare(gaussian(M, V), gauss1(M, V, SD, LogNorm)) :-
    \+ is_list(M), (var(M) ; number(M)), number(V),
    valid(gaussian(0.0, V)), !,
    SD is sqrt(V),
    LogNorm is -0.5*(log(V) + 1.8378770664093453).
dist_prepare(gaussian(Ms, Cs), gauss3(M1, M2, M3, Cs, L11, L21, L22, L31, L32, L33, LogNorm)) :-
    is_list(Ms), Ms = [M1, M2, M3], ground(Cs), is_list(Cs),
    maplist(mean_slot, Ms),
    valid(gaussian([0.0, 0.0, 0.0], Cs)), !,
    Cs = [C11, _, _, C21, C22, _, C31, C32, C33],
    chol3(C11, C21, C22, C31, C32, C33, L11, L21, L22, L31, L32, L33),
    LogNorm is -log(L11*L22*L33) - 1.5*1.8378770664093453.
dist_prepare(D, any(D)).        % (invalid parameters: each use raises dist_check/1's error,
                                %  showing the distribution with its mean bound)

valid(D) :-
    catch(dist_check(D), error(ddc_distribution(_, _), _), fail).

mean_slot(M) :- ( var(M) -> true ; number(M) ).

%!  dist_sample_prepared(+Prepared, -Value) is det.
%
%   A draw from the distribution dist_prepare/2 prepared (its mean
%   variables bound): the draw dist_sample/2 makes from the same state of
%   the random generator.  Throws dist_check/1's errors for a Dist kept as
%   it was.
dist_sample_prepared(any(D), X) :- !,
    dist_check(D),
    dist_sample(D, X).
dist_sample_prepared(G, X) :-
    dist_mean_slots(G, Mean),
    dist_sample_at(G, Mean, X).

%!  dist_mean_slots(+Prepared, -Slots) is semidet.
%
%   Slots is the term of the prepared gaussian's mean variables: (M1, M2,
%   M3) for a 3-D one, M for a 1-D one; fails for a distribution kept as
%   it was.  A caller that holds the mean as such a term (a particle's
%   value of pos(O) ~= (X, Y, Z)) passes it to dist_sample_at/3 and
%   dist_log_density_at/4 instead of binding the variables.
dist_mean_slots(gauss3(M1, M2, M3, _, _, _, _, _, _, _, _), (M1, M2, M3)).
dist_mean_slots(gauss1(M, _, _, _), M).

%!  dist_sample_at(+Prepared, +Mean, -Value) is det.
%
%   dist_sample_prepared/2 with the mean given as a term of the shape of
%   dist_mean_slots/2 (the same draws).
dist_sample_at(gauss3(_, _, _, _, L11, L21, L22, L31, L32, L33, _), (M1, M2, M3), (X1, X2, X3)) :-
    std_normals(3, [Z1, Z2, Z3]),
    X1 is M1 + L11*Z1,
    X2 is M2 + L21*Z1 + L22*Z2,
    X3 is M3 + L31*Z1 + L32*Z2 + L33*Z3.
dist_sample_at(gauss1(_, _, SD, _), M, X) :-
    std_normal(Z),
    X is M + SD*Z.

%!  dist_log_density_at(+Prepared, +Mean, +Value, -LogP) is det.
%
%   dist_log_density_prepared/3 with the mean given as dist_sample_at/3's.
dist_log_density_at(gauss3(_, _, _, Cs, L11, L21, L22, L31, L32, L33, LN), (M1, M2, M3),
                    X, LP) :-
    (   X = (X1, X2, X3), number(X1), number(X2), number(X3)
    ->  Y1 is (X1 - M1)/L11,
        Y2 is (X2 - M2 - L21*Y1)/L22,
        Y3 is (X3 - M3 - L31*Y1 - L32*Y2)/L33,
        LP is -0.5*(Y1*Y1 + Y2*Y2 + Y3*Y3) + LN
    ;   dist_log_density(gaussian([M1, M2, M3], Cs), X, LP)
    ).
dist_log_density_at(gauss1(_, V, SD, LN), M, X, LP) :-
    (   number(X)
    ->  Y is (X - M)/SD,
        LP is -0.5*Y*Y + LN
    ;   dist_log_density(gaussian(M, V), X, LP)
    ).

%!  dist_prepared_factor(+Prepared, -Factor, -LogNorm) is semidet.
%
%   The prepared gaussian's covariance factor and log normaliser, for a
%   caller that draws or weighs in bulk (the batched filter's column
%   library): chol(L11, L21, L22, L31, L32, L33) of a 3-D one, sd(SD) of a
%   1-D one; fails for a distribution kept as it was.
dist_prepared_factor(gauss3(_, _, _, _, L11, L21, L22, L31, L32, L33, LN),
                     chol(L11, L21, L22, L31, L32, L33), LN).
dist_prepared_factor(gauss1(_, _, SD, LN), sd(SD), LN).

%!  dist_log_density_prepared(+Prepared, +Value, -LogP) is det.
%
%   dist_log_density/3 of the distribution dist_prepare/2 prepared.
dist_log_density_prepared(any(D), X, LP) :- !,
    dist_check(D),
    dist_log_density(D, X, LP).
dist_log_density_prepared(G, X, LP) :-
    dist_mean_slots(G, Mean),
    dist_log_density_at(G, Mean, X, LP).

		 /*******************************
		 *        LINEAR ALGEBRA        *
		 *******************************/

cov(K, CT, I, J, X) :-
    N is I*K + J + 1,
    arg(N, CT, X).

%   cholesky(+K, +CovTerm, -Rows): lower-triangular L with L*L^T = Cov;
%   row I is a list of its I+1 non-zero entries.  Fails if the matrix is
%   not positive definite.
cholesky(K, CT, Rows) :-
    chol_rows(0, K, CT, [], Rows).

chol_rows(I, K, CT, Prev, Rows) :-
    (   I >= K
    ->  Rows = []
    ;   chol_row(0, I, K, CT, Prev, [], Row),
        Rows = [Row|Rows1],
        append(Prev, [Row], Prev1),
        I1 is I + 1,
        chol_rows(I1, K, CT, Prev1, Rows1)
    ).

% chol_row(J, I, K, CT, PrevRows, RevSoFar, Row)
chol_row(J, I, K, CT, Prev, Rev, Row) :-
    reverse(Rev, SoFar),
    cov(K, CT, I, J, C),
    (   J =:= I
    ->  dot(SoFar, SoFar, 0, S),
        Dg is C - S,
        Dg > 0,
        L is sqrt(Dg),
        reverse([L|Rev], Row)
    ;   nth0(J, Prev, RowJ),
        dot(SoFar, RowJ, 0, S),
        last(RowJ, LJJ),
        L is (C - S)/LJJ,
        J1 is J + 1,
        chol_row(J1, I, K, CT, Prev, [L|Rev], Row)
    ).

% dot(+Xs, +Ys, +S0, -S): dot product over the shorter of the two lists.
dot([X|Xs], [Y|Ys], S0, S) :- !,
    S1 is S0 + X*Y,
    dot(Xs, Ys, S1, S).
dot(_, _, S, S).

% forward(+Rows, +Ds, +RevYs, -Ys): solve L*Y = D.
forward([], [], Rev, Ys) :-
    reverse(Rev, Ys).
forward([Row|Rows], [D|Ds], Rev, Ys) :-
    reverse(Rev, SoFar),
    dot(Row, SoFar, 0, S),
    last(Row, LII),
    Y is (D - S)/LII,
    forward(Rows, Ds, [Y|Rev], Ys).

		 /*******************************
		 *           DENSITIES          *
		 *******************************/

%!  dist_log_density(+Dist, +Value, -LogP) is det.
%
%   LogP is the natural log of the density (continuous Dist, with respect
%   to Lebesgue measure; for dirichlet, on the first k-1 coordinates) or
%   of the mass (discrete Dist) of Value.  LogP is the float -inf when
%   Value is outside the support, including a value of the wrong type or
%   dimension.  LogP is the float +inf where the density itself is
%   infinite: at 0 (or 1) for beta, gamma and dirichlet with a shape
%   parameter below 1.  Neither infinity may enter SWI-Prolog arithmetic
%   (it raises float_overflow): test for them first.
%   Assumes dist_check(Dist) holds.  Multivariate gaussians
%   and indepGaussians accept the value as a comma tuple or a list (and a
%   plain number when the dimension is 1).  The densities are the exact
%   ones; see the module documentation for where they differ from the
%   original DC system (invgamma Jacobian, student scale factor,
%   normalised logfinite).

dist_log_density(finite(Ps), X, LP) :-
    sum_matching(Ps, X, 0, S),
    log_or_ninf(S, LP).
dist_log_density(propfinite(Ws), X, LP) :-
    sum_matching(Ws, X, 0, S),
    (   S > 0
    ->  sum_weights(Ws, 0, T),
        LP is log(S/T)
    ;   LP is -inf
    ).
dist_log_density(logfinite(Ls), X, LP) :-
    NInf is -inf, max_log(Ls, NInf, Max),
    logsum_matching(Ls, X, Max, 0.0, SM),
    (   SM > 0
    ->  sum_exp(Ls, Max, 0.0, S),
        LP is log(SM) - log(S)
    ;   LP is -inf
    ).
dist_log_density(uniform(Spec), X, LP) :-
    uniform_log_mass(Spec, X, LP).
dist_log_density(bool(P), X, LP) :-
    (   X == true -> log_or_ninf(P, LP)
    ;   X == false -> Q is 1 - P, log_or_ninf(Q, LP)
    ;   LP is -inf
    ).
dist_log_density(val(V), X, LP) :-
    (   same_value(V, X) -> LP = 0.0 ; LP is -inf ).
dist_log_density(gaussian(M, V), X, LP) :-
    (   number(M)
    ->  (   number(X)
        ->  D is X - M,
            LP is -0.5*(D*D/V + log(V) + 1.8378770664093453)
        ;   LP is -inf
        )
    ;   length(M, K),
        (   value_list(X, K, Xs)
        ->  mv_log_density(M, V, K, Xs, LP)
        ;   LP is -inf
        )
    ).
dist_log_density(indepGaussians(Bs), X, LP) :-
    blocks_dim(Bs, 0, K),
    (   value_list(X, K, Xs)
    ->  blocks_log_density(Bs, Xs, 0.0, LP)
    ;   LP is -inf
    ).
dist_log_density(optimalProposal(M, P, H, R, Y), X, LP) :-
    kalman_blocks(optimalProposal, [(M, P, H, R, Y)], Post, _),
    dist_log_density(indepGaussians(Post), X, LP).
dist_log_density(indepOptimalProposals(Bs), X, LP) :-
    kalman_blocks(indepOptimalProposals, Bs, Post, _),
    dist_log_density(indepGaussians(Post), X, LP).
dist_log_density(logIndepOptimalProposals(Bs), V, LP) :-
    kalman_blocks(logIndepOptimalProposals, Bs, Post, LogW),
    (   nonvar(V), V = [X, L], number(L), abs(L - LogW) =< 1.0e-9*max(1.0, abs(LogW))
    ->  dist_log_density(indepGaussians(Post), X, LP)
    ;   LP is -inf
    ).
dist_log_density(logweight(W), _, LP) :-
    logweight_value(logweight(W), W, LP).
dist_log_density(contUniform(A, B), X, LP) :-
    (   number(X), X >= A, X =< B
    ->  LP is -log(B - A)
    ;   LP is -inf
    ).
dist_log_density(beta(A, B), X, LP) :-
    (   number(X), X >= 0, X =< 1
    ->  A1 is A - 1,
        B1 is B - 1,
        Y is 1 - X,
        xlogy(A1, X, T1),
        xlogy(B1, Y, T2),
        LB is lgamma(A) + lgamma(B) - lgamma(A + B),
        add_logs(T1, T2, -LB, LP)
    ;   LP is -inf
    ).
dist_log_density(gamma(K, S), X, LP) :-
    (   number(X), X >= 0
    ->  K1 is K - 1,
        xlogy(K1, X, T1),
        C is -X/S - lgamma(K) - K*log(S),
        add_logs(T1, 0.0, C, LP)
    ;   LP is -inf
    ).
dist_log_density(invgamma(K, S), X, LP) :-
    (   number(X), X > 0
    ->  LP is K*log(S) - lgamma(K) - (K + 1)*log(X) - S/X
    ;   LP is -inf
    ).
dist_log_density(student(Nu), X, LP) :-
    student_log_density(Nu, 0, 1, X, LP).
dist_log_density(student(Nu, M, V), X, LP) :-
    student_log_density(Nu, M, V, X, LP).
dist_log_density(poisson(L), X, LP) :-
    (   integral(X, K), K >= 0
    ->  (   L =:= 0
        ->  (   K =:= 0 -> LP = 0.0 ; LP is -inf )
        ;   LP is K*log(L) - L - lgamma(K + 1)
        )
    ;   LP is -inf
    ).
dist_log_density(exponential(R), X, LP) :-
    (   number(X), X >= 0
    ->  LP is log(R) - R*X
    ;   LP is -inf
    ).
dist_log_density(dirichlet(As), X, LP) :-
    length(As, K),
    (   value_list(X, K, Xs),
        sum_list(Xs, S),
        abs(S - 1) =< 1.0e-9*K,
        \+ ( member(Y, Xs), Y < 0 )
    ->  dirichlet_terms(As, Xs, 0.0, 0.0, 0.0, T, SA, SLG),
        C is lgamma(SA) - SLG,
        add_logs(T, 0.0, C, LP)
    ;   LP is -inf
    ).

log_or_ninf(S, LP) :-
    (   S > 0 -> LP is log(S) ; LP is -inf ).

% xlogy(+A, +Y, -T): T = A*log(Y), with 0*log(0) = 0 and the infinities
% of log(0) made explicit.
xlogy(A, Y, T) :-
    (   A =:= 0 -> T = 0.0
    ;   Y > 0 -> T is A*log(Y)
    ;   A > 0 -> T is -inf
    ;   T is inf
    ).

% add_logs(+T1, +T2, +C, -LP): T1+T2+C where T1, T2 may be infinite
% (never of opposite signs here) and C is finite.
add_logs(T1, T2, C, LP) :-
    (   T1 =:= -inf -> LP is -inf
    ;   T2 =:= -inf -> LP is -inf
    ;   T1 =:= inf -> LP is inf
    ;   T2 =:= inf -> LP is inf
    ;   LP is T1 + T2 + C
    ).

student_log_density(Nu, M, V, X, LP) :-
    (   number(X)
    ->  D is X - M,
        LP is lgamma((Nu + 1)/2) - lgamma(Nu/2)
              - 0.5*log(Nu*pi*V)
              - (Nu + 1)/2*log(1 + D*D/(Nu*V))
    ;   LP is -inf
    ).

integral(X, K) :-
    (   integer(X) -> K = X
    ;   float(X), X =:= X, abs(X) < 1.0e15, X =:= truncate(X) -> K is truncate(X)
    ).

uniform_log_mass(A:C, X, LP) :- !,
    (   integer(A)
    ->  (   integral(X, K), K >= A, K =< C
        ->  LP is -log(C - A + 1)
        ;   LP is -inf
        )
    ;   tuple_list(A, As),
        tuple_list(C, Cs),
        length(As, N),
        (   value_list(X, N, Xs),
            grid_log_mass(As, Cs, Xs, 0.0, LP0)
        ->  LP = LP0
        ;   LP is -inf
        )
    ).
uniform_log_mass(List, X, LP) :-
    count_matching(List, X, 0, C, 0, N),
    (   C > 0
    ->  LP is log(C/N)
    ;   LP is -inf
    ).

grid_log_mass([], [], [], LP, LP).
grid_log_mass([A|As], [C|Cs], [X|Xs], LP0, LP) :-
    integral(X, K), K >= A, K =< C,
    LP1 is LP0 - log(C - A + 1),
    grid_log_mass(As, Cs, Xs, LP1, LP).

%   count_matching(+List, +X, +C0, -C, +N0, -N): C matching elements of N.
count_matching([], _, C, C, N, N).
count_matching([V|Vs], X, C0, C, N0, N) :-
    (   V == X -> C1 is C0 + 1          % the common cases, without a call
    ;   integer(V), integer(X) -> C1 = C0
    ;   same_value(V, X) -> C1 is C0 + 1
    ;   C1 = C0
    ),
    N1 is N0 + 1,
    count_matching(Vs, X, C1, C, N1, N).

sum_matching([], _, S, S).
sum_matching([P:V|T], X, S0, S) :-
    (   same_value(V, X) -> S1 is S0 + P ; S1 = S0 ),
    sum_matching(T, X, S1, S).

logsum_matching([], _, _, S, S).
logsum_matching([L:V|T], X, Max, S0, S) :-
    (   same_value(V, X)
    ->  lexp(L, Max, W),
        S1 is S0 + W
    ;   S1 = S0
    ),
    logsum_matching(T, X, Max, S1, S).

%   same_value(+Entry, +Value): numbers by value, compounds argument-wise,
%   an unbound Entry matches anything.
same_value(V, X) :-
    V == X, !.
same_value(V, _) :-
    var(V), !.
same_value(V, X) :-
    number(V), !,
    number(X),
    V =:= X.
same_value(V, X) :-
    compound(V),
    compound(X),
    compound_name_arity(V, N, A),
    compound_name_arity(X, N, A),
    same_args(A, V, X).

same_args(0, _, _) :- !.
same_args(I, V, X) :-
    arg(I, V, A),
    arg(I, X, B),
    same_value(A, B),
    I1 is I - 1,
    same_args(I1, V, X).

mv_log_density([M1, M2], [C11, _, C21, C22], 2, [X1, X2], LP) :- !,
    D1 is X1 - M1,
    D2 is X2 - M2,
    Det is C11*C22 - C21*C21,
    LP is -0.5*(C22*D1*D1 - 2*C21*D1*D2 + C11*D2*D2)/Det
          - 0.5*log(Det) - 1.8378770664093453.
mv_log_density([M1, M2, M3], [C11, _, _, C21, C22, _, C31, C32, C33], 3,
               [X1, X2, X3], LP) :- !,
    chol3(C11, C21, C22, C31, C32, C33, L11, L21, L22, L31, L32, L33),
    Y1 is (X1 - M1)/L11,
    Y2 is (X2 - M2 - L21*Y1)/L22,
    Y3 is (X3 - M3 - L31*Y1 - L32*Y2)/L33,
    LP is -0.5*(Y1*Y1 + Y2*Y2 + Y3*Y3) - log(L11*L22*L33)
          - 1.5*1.8378770664093453.
mv_log_density(Ms, Cs, K, Xs, LP) :-
    CT =.. [c|Cs],
    cholesky(K, CT, Rows),
    maplist(diff, Xs, Ms, Ds),
    forward(Rows, Ds, [], Ys),
    dot(Ys, Ys, 0, Q),
    log_diag(Rows, 0.0, LogDet2),       % sum log L_ii = 0.5 log det
    LP is -0.5*Q - LogDet2 - 0.5*K*1.8378770664093453.

diff(X, M, D) :- D is X - M.

log_diag([], S, S).
log_diag([Row|Rows], S0, S) :-
    last(Row, L),
    S1 is S0 + log(L),
    log_diag(Rows, S1, S).

blocks_dim([], K, K).
blocks_dim([(M, _)|Bs], K0, K) :-
    (   number(M) -> K1 is K0 + 1 ; length(M, N), K1 is K0 + N ),
    blocks_dim(Bs, K1, K).

blocks_log_density([], [], LP, LP).
blocks_log_density([(M, C)|Bs], Xs, LP0, LP) :-
    (   number(M)
    ->  Xs = [X|Xs1],
        D is X - M,
        L is -0.5*(D*D/C + log(C) + 1.8378770664093453)
    ;   length(M, K),
        length(Ys, K),
        append(Ys, Xs1, Xs),
        mv_log_density(M, C, K, Ys, L)
    ),
    LP1 is LP0 + L,
    blocks_log_density(Bs, Xs1, LP1, LP).

dirichlet_terms([], [], T, SA, SLG, T, SA, SLG).
dirichlet_terms([A|As], [X|Xs], T0, SA0, SLG0, T, SA, SLG) :-
    A1 is A - 1,
    xlogy(A1, X, T1),
    add_logs(T0, T1, 0.0, T2),
    SA1 is SA0 + A,
    SLG1 is SLG0 + lgamma(A),
    dirichlet_terms(As, Xs, T2, SA1, SLG1, T, SA, SLG).

		 /*******************************
		 *       VALUES AND TUPLES      *
		 *******************************/

%   tuple_list(+Tuple, -List): (A,B,C) <-> [A,B,C]; a non-tuple is [X].
tuple_list(T, L) :-
    (   nonvar(T), T = (A, B)
    ->  L = [A|L1],
        tuple_list(B, L1)
    ;   L = [T]
    ).

%   list_value(+Xs, -Value): a one-element list gives the element, longer
%   lists a comma tuple.
list_value([X], V) :- !,
    V = X.
list_value([X|Xs], (X, V)) :-
    list_value(Xs, V).

%   value_list(+Value, +K, -Xs): Value as a list of K numbers, accepting a
%   comma tuple, a list, or (K = 1) a number.
value_list(X, K, Xs) :-
    (   is_list(X)
    ->  Xs = X,
        length(Xs, K)
    ;   tuple_list(X, Xs),
        length(Xs, K)
    ),
    all_numbers(Xs).

all_numbers([]).
all_numbers([X|Xs]) :-
    number(X),
    all_numbers(Xs).

		 /*******************************
		 *        CLASSIFICATION        *
		 *******************************/

%!  dist_discrete(+Dist) is semidet.
%
%   True if Dist is a discrete distribution (a mass function): finite,
%   propfinite, logfinite, uniform (both forms), bool, val, poisson and
%   logweight (a weight, counted as a mass).

dist_discrete(finite(_)).
dist_discrete(propfinite(_)).
dist_discrete(logfinite(_)).
dist_discrete(uniform(_)).
dist_discrete(bool(_)).
dist_discrete(val(_)).
dist_discrete(poisson(_)).
dist_discrete(logweight(_)).

%!  dist_support(+Dist, -Pairs) is semidet.
%
%   For a distribution with finite support (finite, propfinite,
%   logfinite, uniform(List), uniform(A:C), bool, val), Pairs is the list
%   of Prob-Value with the probabilities normalised to sum to 1, equal
%   values (same_value: 1 and 1.0 are equal) merged in order of first
%   appearance, and zero-probability values left out.  Fails for other
%   distributions.  Assumes dist_check(Dist) holds.

dist_support(finite(Ps), Pairs) :-
    support_from_weights(Ps, Pairs).
dist_support(propfinite(Ws), Pairs) :-
    support_from_weights(Ws, Pairs).
dist_support(logfinite(Ls), Pairs) :-
    NInf is -inf, max_log(Ls, NInf, Max),
    findall(W:V, ( member(L:V, Ls), lexp(L, Max, W) ), Ws),
    support_from_weights(Ws, Pairs).
dist_support(uniform(Spec), Pairs) :-
    (   nonvar(Spec), Spec = A:C
    ->  (   integer(A)
        ->  numlist(A, C, Vs)
        ;   tuple_list(A, As),
            tuple_list(C, Cs),
            findall(V, ( maplist(between, As, Cs, Xs), list_value(Xs, V) ), Vs)
        )
    ;   Vs = Spec
    ),
    findall(1:V, member(V, Vs), Ws),
    support_from_weights(Ws, Pairs).
dist_support(bool(P), Pairs) :-
    Q is 1 - P,
    support_from_weights([P:true, Q:false], Pairs).
dist_support(val(V), [1.0-V]).

support_from_weights(Ws, Pairs) :-
    merge_weights(Ws, [], Rev),
    reverse(Rev, Merged),
    sum_weights(Merged, 0, S),
    findall(P-V, ( member(W:V, Merged), W > 0, P is W/S ), Pairs).

merge_weights([], Acc, Acc).
merge_weights([W:V|T], Acc0, Acc) :-
    (   select(W0:V0, Acc0, W1:V0, Acc1), same_value(V0, V), same_value(V, V0)
    ->  W1 is W0 + W
    ;   Acc1 = [W:V|Acc0]
    ),
    merge_weights(T, Acc1, Acc).

%!  dist_mean(+Dist, -Mean) is semidet.
%
%   Mean is the expectation of Dist, where it is defined and the values
%   are numeric: a number for 1-D distributions, a comma tuple for the
%   multivariate gaussian and indepGaussians (a number when the dimension
%   is 1), a list for dirichlet.  Fails for non-numeric discrete values
%   (bool, finite over atoms, ...), for invgamma with Shape =< 1 and for
%   student with Nu =< 1.

dist_mean(finite(Ps), M) :-
    weighted_mean(Ps, M).
dist_mean(propfinite(Ws), M) :-
    weighted_mean(Ws, M).
dist_mean(logfinite(Ls), M) :-
    dist_support(logfinite(Ls), Pairs),
    pairs_mean(Pairs, 0, M).
dist_mean(uniform(Spec), M) :-
    (   nonvar(Spec), Spec = A:C, integer(A)
    ->  M is (A + C)/2
    ;   dist_support(uniform(Spec), Pairs),
        pairs_mean(Pairs, 0, M)
    ).
dist_mean(val(V), V) :-
    number(V).
dist_mean(gaussian(M, _), Mean) :-
    (   number(M) -> Mean = M ; list_value(M, Mean) ).
dist_mean(indepGaussians(Bs), Mean) :-
    findall(X, ( member((M, _), Bs), ( number(M) -> X = M ; member(X, M) ) ), Xs),
    list_value(Xs, Mean).
dist_mean(contUniform(A, B), M) :-
    M is (A + B)/2.
dist_mean(beta(A, B), M) :-
    M is A/(A + B).
dist_mean(gamma(K, S), M) :-
    M is K*S.
dist_mean(invgamma(K, S), M) :-
    K > 1,
    M is S/(K - 1).
dist_mean(student(Nu), 0) :-
    Nu > 1.
dist_mean(student(Nu, M, _), M) :-
    Nu > 1.
dist_mean(poisson(L), L).
dist_mean(exponential(R), M) :-
    M is 1/R.
dist_mean(dirichlet(As), M) :-
    sum_list(As, S),
    divide_all(As, S, M).

weighted_mean(Ws, M) :-
    support_from_weights(Ws, Pairs),
    pairs_mean(Pairs, 0, M).

pairs_mean([], M, M).
pairs_mean([P-V|T], M0, M) :-
    number(V),
    M1 is M0 + P*V,
    pairs_mean(T, M1, M).

		 /*******************************
		 *           MESSAGES           *
		 *******************************/

prolog:error_message(ddc_distribution(Dist, Cause)) -->
    dist_message(Dist, Cause).

prolog:message(ddc_distribution(Dist, Cause)) -->
    dist_message(Dist, Cause).

dist_message(Dist, Cause) -->
    [ 'Invalid distribution ~p: '-[Dist] ],
    cause_message(Cause).

cause_message(unbound) --> !,
    [ 'the distribution is unbound' ].
cause_message(unknown_distribution) --> !,
    [ 'unknown distribution (known: finite, propfinite, logfinite, uniform, bool, val, gaussian, indepGaussians, contUniform, beta, gamma, invgamma, student, poisson, exponential, dirichlet, optimalProposal, indepOptimalProposals, logIndepOptimalProposals, logweight)' ].
cause_message(not_a_number(X)) --> !,
    [ 'parameter ~p is not a number'-[X] ].
cause_message(not_finite(X)) --> !,
    [ 'parameter ~p is not finite'-[X] ].
cause_message(not_a_list(X)) --> !,
    [ '~p is not a list'-[X] ].
cause_message(malformed_entry(E)) --> !,
    [ 'entry ~p is not of the form Probability:Value'-[E] ].
cause_message(negative_probability(P)) --> !,
    [ 'probability ~p is negative'-[P] ].
cause_message(probabilities_sum(S)) --> !,
    [ 'the probabilities sum to ~p, not 1'-[S] ].
cause_message(negative_weight(W)) --> !,
    [ 'weight ~p is negative'-[W] ].
cause_message(empty_support) --> !,
    [ 'the support is empty' ].
cause_message(not_integer(X)) --> !,
    [ 'bound ~p is not an integer'-[X] ].
cause_message(probability_out_of_range(P)) --> !,
    [ 'probability ~p is not in [0,1]'-[P] ].
cause_message(negative_variance) --> !,
    [ 'the variance is negative' ].
cause_message(not_positive(Param)) --> !,
    [ 'the ~w must be positive'-[Param] ].
cause_message(negative(Param)) --> !,
    [ 'the ~w must not be negative'-[Param] ].
cause_message(dimension_mismatch(What, Expected, Found)) --> !,
    [ 'the ~w has ~p elements, expected ~p'-[What, Found, Expected] ].
cause_message(not_symmetric) --> !,
    [ 'the covariance matrix is not symmetric' ].
cause_message(not_positive_definite) --> !,
    [ 'the covariance matrix is not positive definite' ].
cause_message(malformed_block(B)) --> !,
    [ 'block ~p is not of the form (Mean,Variance) or (MeanList,CovList)'-[B] ].
cause_message(malformed_kalman_block(B)) --> !,
    [ 'block ~p is not of the form (MeanList,CovList,HList,RList,YList)'-[B] ].
cause_message(singular_innovation) --> !,
    [ 'the innovation covariance H P H\' + R is singular' ].
cause_message(no_sampler) --> !,
    [ 'logweight/1 only weighs an observation; it cannot be sampled' ].
cause_message(Cause) -->
    [ '~p'-[Cause] ].

		 /*******************************
		 *   KALMAN (OPTIMAL PROPOSALS)  *
		 *******************************/

%   kalman_blocks(+D, +Blocks, -Posterior, -LogW): Posterior is the list of
%   indepGaussians blocks (M', P') of the Kalman updates of Blocks (see the
%   module documentation for the equations) and LogW the sum of their log
%   predictive densities log N(Y; H M, S).  D names the distribution in
%   errors.
kalman_blocks(D, Bs, Post, LogW) :-
    must_list(D, Bs),
    (   Bs == [] -> dist_error(D, empty_support) ; true ),
    foldl(kalman_block_acc(D), Bs, Post, 0.0, LogW).

kalman_block_acc(D, B, (M1, P1), W0, W) :-
    kalman_block(D, B, (M1, P1), W1),
    W is W0 + W1.

%   kalman_block(+D, +Block, -(M1, P1), -LogW): one block's update; M1 a
%   list of k means, P1 the k*k posterior covariance row-major.
kalman_block(D, B, (M1, P1f), LogW) :-
    (   nonvar(B), B = (M0, Pf0, Hf0, Rf0, Y0)
    ->  true
    ;   dist_error(D, malformed_kalman_block(B))
    ),
    maplist(num_list(D), [M0, Pf0, Hf0, Rf0, Y0], [M, Pf, Hf, Rf, Y]),
    length(M, K), length(Y, Mm),
    (   K > 0, Mm > 0 -> true ; dist_error(D, empty_support) ),
    rows(D, covariance, Pf, K, K, P),
    rows(D, measurement_matrix, Hf, Mm, K, H),
    rows(D, measurement_covariance, Rf, Mm, Mm, R),
    mat_vec(H, M, HM),
    maplist(kdiff, Y, HM, E),                    % innovation Y - H M
    transpose_rows(H, Ht),
    mat_mul(P, Ht, PHt),                        % P H'
    mat_mul(H, PHt, HPHt),
    maplist(maplist(sum2), HPHt, R, S),         % S = H P H' + R
    (   mat_inverse(S, Si, DetS), DetS > 0
    ->  true
    ;   dist_error(D, singular_innovation)
    ),
    mat_mul(PHt, Si, G),                        % gain K = P H' S^-1
    mat_vec(G, E, GE),
    maplist(sum2, M, GE, M1),                   % M' = M + K (Y - H M)
    transpose_rows(PHt, HP),                    % H P = (P H')'  (P symmetric)
    mat_mul(G, HP, GHP0),                       % K H P
    transpose_rows(GHP0, GHPt),                 % (K S K' is symmetric; average
    maplist(maplist(half_sum), GHP0, GHPt, GHP),%  out rounding)
    maplist(maplist(kdiff), P, GHP, P1),         % P' = P - K H P
    append(P1, P1f),
    mat_vec(Si, E, SiE),
    dot(E, SiE, Q),
    LogW is -0.5*(Q + log(DetS) + Mm*1.8378770664093453),
    check_block(D, (M1, P1f)).

num_list(D, X, L) :-
    (   is_list(X) -> L = X ; L = [X] ),
    forall(member(V, L), must_number(D, V)).

rows(D, What, Flat, NR, NC, Rows) :-
    length(Flat, N),
    N0 is NR*NC,
    (   N =:= N0 -> true ; dist_error(D, dimension_mismatch(What, N0, N)) ),
    length(Rows, NR),
    maplist(row_length(NC), Rows),
    append(Rows, Flat).

row_length(N, R) :- length(R, N).

kdiff(A, B, C) :- C is A - B.
sum2(A, B, C) :- C is A + B.
half_sum(A, B, C) :- C is (A + B)/2.

dot(Xs, Ys, D) :- foldl(dot_acc, Xs, Ys, 0.0, D).
dot_acc(X, Y, D0, D) :- D is D0 + X*Y.

mat_vec(A, X, Y) :- maplist(row_dot(X), A, Y).
row_dot(X, Row, Y) :- dot(Row, X, Y).

transpose_rows([], []) :- !.
transpose_rows([[]|_], []) :- !.
transpose_rows(Rows, [Col|Cols]) :-
    maplist(head_tail, Rows, Col, Rests),
    transpose_rows(Rests, Cols).

head_tail([H|T], H, T).

mat_mul(A, B, C) :-
    transpose_rows(B, Bt),
    maplist(row_times(Bt), A, C).
row_times(Bt, Row, CRow) :- maplist(row_dot(Row), Bt, CRow).

%   mat_inverse(+A, -Inv, -Det): Gauss-Jordan elimination with partial
%   pivoting; fails when A is singular.
mat_inverse(A, Inv, Det) :-
    length(A, N),
    numlist(1, N, Is),
    maplist(identity_row(N), Is, Id),
    maplist(append, A, Id, Aug0),
    gauss_jordan(Is, N, Aug0, Aug, 1.0, Det),
    maplist(drop_left(N), Aug, Inv).

identity_row(N, I, Row) :-
    numlist(1, N, Js),
    maplist(kronecker(I), Js, Row).
kronecker(I, J, X) :- ( I =:= J -> X = 1.0 ; X = 0.0 ).

drop_left(N, Row, Right) :- length(Left, N), append(Left, Right, Row).

gauss_jordan([], _, Aug, Aug, Det, Det).
gauss_jordan([C|Cs], N, Aug0, Aug, Det0, Det) :-
    C0 is C - 1,
    length(Done, C0),
    append(Done, Rest, Aug0),
    pivot_row(Rest, C, Piv, Others),
    nth1(C, Piv, PV),
    abs(PV) > 1.0e-300,
    (   Rest = [Piv|_] -> Sign = 1.0 ; Sign = -1.0 ),
    Det1 is Det0*PV*Sign,
    maplist(div_by(PV), Piv, PivN),
    append(Done, [PivN|Others], Aug1),
    numlist(1, N, Ks),
    maplist(eliminate(C, PivN), Ks, Aug1, Aug2),
    gauss_jordan(Cs, N, Aug2, Aug, Det1, Det).

%   the row of Rows with the largest |entry| in column C first
pivot_row(Rows, C, Piv, Others) :-
    foldl(best_row(C), Rows, none, Piv),
    selectchk(Piv, Rows, Others).

best_row(C, R, none, R) :- !, nth1(C, R, _).
best_row(C, R, B, Best) :-
    nth1(C, R, X), nth1(C, B, Y),
    (   abs(X) > abs(Y) -> Best = R ; Best = B ).

div_by(P, X, Y) :- Y is X/P.

eliminate(C, PivN, K, Row, Row1) :-
    (   K =:= C
    ->  Row1 = Row
    ;   nth1(C, Row, F),
        maplist(sub_scaled(F), Row, PivN, Row1)
    ).
sub_scaled(F, X, P, Y) :- Y is X - F*P.

%   logweight_value(+D, +W, -LP): the log weight W, a number or (as YAP
%   evaluated it in the original's tracking example) a one-element list.
logweight_value(D, W, LP) :-
    (   number(W) -> LP0 = W
    ;   W = [LP0], number(LP0) -> true
    ;   dist_error(D, not_a_number(W))
    ),
    (   float(LP0), LP0 =\= LP0 -> dist_error(D, not_a_number(W)) ; true ),
    LP is float(LP0).
