/*  plunit: resample_preserving/6 (mixture resampling): every stratum of positive mass keeps
    its mass and at least Keep particles, copies stay within their stratum, the weights are
    normalised, and the errors of bad input.
*/
:- use_module('../../../prolog/ddc/filter/ddc_weights').
:- use_module(library(plunit)).
:- use_module(library(apply)).
:- use_module(library(lists)).
:- use_module(library(pairs)).

log_weight(W, L) :- ( W =:= 0 -> L is -inf ; L is log(W) ).

%   stratum_masses(+Is, +LWs, +Strata, -Masses): Stratum-Mass pairs of the copies Is
stratum_masses(Is, LWs, Strata, Masses) :-
    maplist([I, L, S-W]>>(nth0(I, Strata, S), W is exp(L)), Is, LWs, Pairs),
    msort(Pairs, Sorted),
    group_pairs_by_key(Sorted, Groups),
    maplist([S-Ws, S-M]>>sum_list(Ws, M), Groups, Masses).

stratum_counts(Is, Strata, Counts) :-
    maplist([I, S]>>nth0(I, Strata, S), Is, Ss),
    msort(Ss, Sorted),
    clumped(Sorted, Counts).

close_to(A, B) :- abs(A - B) < 1e-12.

:- begin_tests(ddc_resample_preserving).

test(small_stratum_kept_with_its_mass) :-
    Ws = [0.4, 0.3, 0.2999, 0.0001],
    maplist(log_weight, Ws, LWs),
    Strata = [0, 0, 0, 1],
    resample_preserving(LWs, Strata, 2, [0.5], Is, LWs1),
    assertion(msort(Is, Is)),
    assertion(length(Is, 4)),
    stratum_counts(Is, Strata, Counts),
    assertion(Counts == [0-2, 1-2]),
    stratum_masses(Is, LWs1, Strata, [0-M0, 1-M1]),
    assertion(close_to(M0, 0.9999)),
    assertion(close_to(M1, 0.0001)),
    % the copies of stratum 0 are systematic among its own particles
    assertion(Is == [0, 2, 3, 3]).

test(random_strata_keep_masses_and_keep, [forall(between(1, 30, Seed))]) :-
    set_random(seed(Seed)),
    N is 20 + random(200),
    K is 1 + random(5),
    length(Ws0, N),
    maplist([W]>>(R is random_float, ( R < 0.1 -> W = 0.0 ; W is random_float ** 4 )), Ws0),
    sum_list(Ws0, T),
    T > 0,
    maplist([W, V]>>(V is W / T), Ws0, Ws),
    length(Strata, N),
    maplist([S]>>(S is random(K)), Strata),
    maplist(log_weight, Ws, LWs),
    Keep is 1 + random(4),
    U is random_float,
    resample_preserving(LWs, Strata, Keep, [U], Is, LWs1),
    assertion(length(Is, N)),
    assertion(msort(Is, Is)),
    maplist([L, W]>>(W is exp(L)), LWs1, New),
    sum_list(New, Total),
    assertion(abs(Total - 1) < 1e-9),
    % every copy is of a particle of positive weight, and every stratum keeps its mass
    assertion(forall(member(I, Is), (nth0(I, Ws, W), W > 0))),
    findall(S-M, (between(0, K, S), stratum_mass(Ws, Strata, S, M), M > 0), Before),
    stratum_masses(Is, LWs1, Strata, After),
    pairs_keys(Before, SB), pairs_keys(After, SA),
    assertion(SB == SA),
    assertion(forall((member(S-M, Before), memberchk(S-M1, After)), abs(M - M1) < 1e-9)),
    % at least Keep copies each (fewer only when the strata are too many for Keep)
    length(Before, KB),
    Least is min(Keep, N // KB),
    stratum_counts(Is, Strata, Counts),
    assertion(forall(member(_-C, Counts), C >= Least)).

test(zero_mass_stratum_gets_none) :-
    maplist(log_weight, [0.5, 0.5, 0.0, 0.0], LWs),
    resample_preserving(LWs, [0, 0, 1, 1], 1, [0.3], Is, _),
    assertion(Is == [0, 0, 1, 1]).

test(strata_of_another_length, [error(domain_error(same_length(2), [0]))]) :-
    resample_preserving([-0.7, -0.7], [0], 1, [0.5], _, _).

test(keep_not_positive, [error(type_error(positive_integer, 0))]) :-
    resample_preserving([-0.7, -0.7], [0, 1], 0, [0.5], _, _).

test(no_uniform, [error(domain_error(enough_uniforms(1), []))]) :-
    resample_preserving([-0.7, -0.7], [0, 1], 1, [], _, _).

:- end_tests(ddc_resample_preserving).

stratum_mass(Ws, Strata, S, M) :-
    foldl([W, S1, M0, M1]>>(S1 == S -> M1 is M0 + W ; M1 = M0), Ws, Strata, 0.0, M).
