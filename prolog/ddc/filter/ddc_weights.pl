/*  ddc_weights.pl -- a particle filter's weights and resampling: the one place
    that states their rules.

    The filter predicates (filter_step/4, filter_resample/2, ...) hold the
    particles and return each step's log weights; what is done with them
    (normalising, the running log-likelihood, the effective sample size,
    when to resample and which particles to copy) is stated here, once,
    for the weighted belief of swipl users (ddc_belief.pl) and for the
    Python bridge (ddc_bridge.pl, whose bridge.Filter keeps no rule of its
    own).
*/

:- module(ddc_weights,
          [ weights_uniform/2,          % +N, -LogWeights
            weights_update/6,           % +LogWeights0, +StepLogWeights, -LogWeights,
                                        % -Increment, -ESS, -Infinite
            weights_reweight/5,         % +LogWeights0, +LogFactors, -LogWeights,
                                        % -Increment, -ESS
            weights_ess/2,              % +LogWeights, -ESS
            weights_normalised/2,       % +LogWeights, -Weights
            resample_needed/3,          % +ESS, +Threshold, +N
            resample_draws/3,           % +Scheme, +Weights, -K
            resample_indices/4,         % +Scheme, +Weights, +Uniforms, -Indices
            resample_log_weights/5,     % +Scheme, +LogWeights, +Uniforms, -K, -Indices
            resample_preserving/6,      % +LogWeights, +Strata, +Keep, +Uniforms, -Indices,
                                        % -LogWeights1
            numpy_sum/2                 % +Xs, -Sum
          ]).

:- use_module(library(apply)).
:- use_module(library(lists)).
:- use_module(library(error)).
:- use_module(library(pairs)).
:- use_module('../batch/ddc_batch_col', [col_weights_update/6, col_systematic_indices/3]).
%   (the passes over the particles in C where the column library is loaded)

%   Arithmetic compiled to virtual-machine instructions (local to this
%   file; see ddc.pl): a step's weights are a few passes over N floats.
:- set_prolog_flag(optimise, true).

/** <module> Particle weights and resampling

Log weights are lists of floats, one per particle, normalised (their
exponentials sum to 1) except where said; -inf is weight 0.  No state is
kept here: the caller holds the weights (the swipl belief in a global
variable, bridge.Filter in a numpy array it hands back at each step) and
the random numbers (the uniforms of resample_indices/4 come from the
caller's stream: the belief's Prolog random stream, bridge.Filter's numpy
Generator).

A step (weights_update/6): the step's log weights are added to the old
ones (NaN counts as -inf); if some particle's is +inf, those particles
get log weight 0 and all others -inf (print or log a warning); the
increment is the log of the weighted mean likelihood, log(sum(exp(C))),
added to the running log-likelihood; the new log weights are C minus the
increment.  If every particle gets weight 0 the increment is -inf and the
caller undoes the step.  Resample (resample_needed/3) when the effective
sample size 1/sum(w^2) falls below Threshold*N; the weights are then
uniform (weights_uniform/2).
*/

%!  weights_uniform(+N:positive_integer, -LogWeights:list(float)) is det.
%
%   N log weights -log(N).
weights_uniform(N, LWs) :-
    must_be(positive_integer, N),
    L is -log(N),
    length(LWs, N),
    maplist(=(L), LWs).

%!  weights_update(+LogWeights0:list, +StepLogWeights:list, -LogWeights:list, -Increment:float,
%!                 -ESS:float, -Infinite:boolean) is det.
%
%   The normalised log weights after a step whose log weights are
%   StepLogWeights (see the module comment).  Increment is the log of the
%   weighted mean likelihood of the step; when it is -inf (every particle
%   has weight 0) LogWeights is LogWeights0 and ESS 0.0.  Infinite is true
%   when some particle's likelihood was infinite (only those were kept).
%
%   @error domain_error(same_length(N), StepLogWeights) if the lists'
%          lengths differ.
weights_update(LWs0, Step, LWs, Inc, ESS, Infinite) :-    % (in C where the library is)
    col_weights_update(LWs0, Step, LWs1, Inc1, ESS1, Infinite1),
    !,
    LWs = LWs1, Inc = Inc1, ESS = ESS1, Infinite = Infinite1.
weights_update(LWs0, Step, LWs, Inc, ESS, Infinite) :-
    length(LWs0, N),
    (   length(Step, N) -> true ; domain_error(same_length(N), Step) ),
    NegInf is -inf,
    combine(LWs0, Step, Comb0, NegInf, Max0),
    (   Max0 =:= inf
    ->  Infinite = true,
        maplist(keep_infinite, Comb0, Comb),
        Max = 0.0
    ;   Infinite = false,
        Comb = Comb0,
        Max = Max0
    ),
    (   Max =:= -inf
    ->  Inc = Max
    ;   sum_exp(Comb, Max, 0.0, Sum),
        Inc is Max + log(Sum)
    ),
    (   Inc =:= -inf
    ->  LWs = LWs0,
        ESS = 0.0
    ;   normalise(Comb, Inc, LWs, ESS)
    ).

%   combine(+L0s, +Ls, -Cs, +Max0, -Max): Cs the combined log weights (NaN
%   counts as -inf; arithmetic that yields an infinity raises
%   float_overflow, so the infinities are handled before they reach it),
%   Max the largest (max/2 of two infinities overflows).  (The passes over
%   the particles are plain recursions: a step makes a few of them.)
combine([], [], [], M, M).
combine([L0|L0s], [L|Ls], [C|Cs], M0, M) :-
    (   L =:= L, L > -inf, L0 > -inf    % (L =:= L: not NaN)
    ->  (   L =:= inf -> C = L ; C is L0 + L )
    ;   C is -inf
    ),
    (   C > M0 -> M1 = C ; M1 = M0 ),
    combine(L0s, Ls, Cs, M1, M).

keep_infinite(C, K) :-
    (   C =:= inf -> K = 0.0 ; K is -inf ).

%   sum_exp(+Cs, +M, +S0, -S): S0 plus the sum of exp(C - M), from left to right.
sum_exp([], _, S, S).
sum_exp([L|Ls], M, S0, S) :-
    (   L =:= -inf -> S1 = S0 ; S1 is S0 + exp(L - M) ),
    sum_exp(Ls, M, S1, S).

%   normalise(+Comb, +Inc, -LWs, -ESS): LWs = Comb - Inc, ESS = 1/sum(exp(LW)^2)
normalise(Comb, Inc, LWs, ESS) :-
    normalise(Comb, Inc, LWs, 0.0, S),
    ESS is 1 / S.

normalise([], _, [], S, S).
normalise([C|Cs], Inc, [L|Ls], S0, S) :-
    (   C =:= -inf
    ->  L = C, S1 = S0
    ;   L is C - Inc,
        W is exp(L),
        S1 is S0 + W*W
    ),
    normalise(Cs, Inc, Ls, S1, S).

%!  weights_reweight(+LogWeights0:list, +LogFactors:list, -LogWeights:list, -Increment:float,
%!                   -ESS:float) is det.
%
%   Each weight multiplied by exp(LogFactor) and the weights normalised
%   again: an importance correction computed by the caller.  LogFactors
%   are finite or -inf.  Increment is the log of the weighted mean factor
%   (-inf, with LogWeights LogWeights0, when no particle keeps a weight).
%
%   @error domain_error(same_length(N), LogFactors) if the lists' lengths
%          differ.
weights_reweight(LWs0, Factors, LWs, Inc, ESS) :-
    weights_update(LWs0, Factors, LWs, Inc, ESS, _).

%!  weights_ess(+LogWeights:list, -ESS:float) is det.
%
%   The effective sample size 1/sum(w^2) of normalised log weights.
weights_ess(LWs, ESS) :-
    foldl(add_square, LWs, 0.0, S),
    ESS is 1 / S.

add_square(L, S0, S) :-
    exp_weight(L, W),
    S is S0 + W*W.

%!  weights_normalised(+LogWeights:list, -Weights:list(float)) is det.
%
%   The weights exp(L) of normalised log weights (0.0 for -inf).
weights_normalised([], []).
weights_normalised([L|Ls], [W|Ws]) :-
    exp_weight(L, W),
    weights_normalised(Ls, Ws).

exp_weight(L, W) :-
    (   L =:= -inf -> W = 0.0 ; W is exp(L) ).

%!  resample_needed(+ESS:float, +Threshold:float, +N:integer) is semidet.
%
%   True when the particles are to be resampled: ESS < Threshold*N.
resample_needed(ESS, Th, N) :-
    ESS < Th * N.

%!  resample_log_weights(+Scheme, +LogWeights:list(float), +Uniforms:list(float),
%!                       -K:integer, -Indices:list(integer)) is det.
%
%   resample_indices/4 of the weights of the normalised LogWeights
%   (weights_normalised/2), K the uniforms it used (resample_draws/3).  A
%   systematic resampling runs in the column library where it is loaded
%   (the same operations in the same order: the same indices).
resample_log_weights(systematic, LWs, [U|_], 1, Is) :-
    col_systematic_indices(LWs, U, Is0),
    !,
    Is = Is0.
resample_log_weights(Scheme, LWs, Us, K, Is) :-
    weights_normalised(LWs, Ws),
    resample_draws(Scheme, Ws, K),
    resample_indices(Scheme, Ws, Us, Is).

%!  resample_draws(+Scheme, +Weights:list(float), -K:integer) is det.
%
%   The number of uniforms resample_indices/4 uses for Weights: 1
%   (systematic), N (multinomial) or R = N - sum(floor(N w_i))
%   (residual), so that a caller draws from its stream exactly those.
resample_draws(Scheme, Ws, K) :-
    must_be(oneof([systematic, multinomial, residual]), Scheme),
    must_be(list(number), Ws),
    resample_draws_(Scheme, Ws, K).

resample_draws_(systematic, _, 1).
resample_draws_(multinomial, Ws, N) :-
    length(Ws, N).
resample_draws_(residual, Ws, R) :-
    length(Ws, N),
    kept_copies(Ws, N, 0, Kept),
    R is N - Kept.

kept_copies([], _, K, K).
kept_copies([W|Ws], N, K0, K) :-
    K1 is K0 + floor(N * W),
    kept_copies(Ws, N, K1, K).

%!  resample_indices(+Scheme, +Weights:list(float), +Uniforms:list(float),
%!                   -Indices:list(integer)) is det.
%
%   N ancestor indices (0-based, ascending) for N normalised Weights, from
%   uniform numbers in [0, 1):
%     - systematic: one offset U (the first uniform), positions (U+k)/N:
%       particle i is copied floor(N w_i) or ceil(N w_i) times;
%     - multinomial: the first N uniforms, sorted, are the positions;
%     - residual: floor(N w_i) copies of each particle, the R = N - sum of
%       the floors that remain drawn as multinomial (the first R uniforms)
%       from the residuals N w_i - floor(N w_i), normalised by their
%       pairwise sum (numpy_sum/2).
%   Each position takes the first particle whose cumulative weight exceeds
%   it, the last particle any position that none exceeds (its cumulative
%   weight counts as 1).  N uniforms always suffice; resample_draws/3 says
%   how many are used.
%
%   @error domain_error(enough_uniforms(K), Uniforms) if fewer than the K
%   the scheme needs are given.
resample_indices(Scheme, Ws, Us, Is) :-
    must_be(oneof([systematic, multinomial, residual]), Scheme),
    must_be(list(number), Ws),
    must_be(list(number), Us),
    resample_indices_(Scheme, Ws, Us, Is).

resample_indices_(systematic, Ws, Us, Is) :-
    first_uniforms(1, Us, [U]),
    length(Ws, N),
    systematic_positions(0, N, U, Ps),
    walk(Ws, Ps, Is).
resample_indices_(multinomial, Ws, Us, Is) :-
    length(Ws, N),
    first_uniforms(N, Us, Draws),
    msort(Draws, Ps),
    walk(Ws, Ps, Is).
resample_indices_(residual, Ws, Us, Is) :-
    length(Ws, N),
    maplist(residual_copies(N), Ws, Copies),
    sum_list(Copies, Kept),
    Rest is N - Kept,
    N1 is N - 1,
    numlist(0, N1, Ids),
    foldl(repeat_index, Ids, Copies, Det, []),
    (   Rest =:= 0
    ->  Is = Det
    ;   maplist(residual_weight(N), Ws, Copies, Rs0),
        numpy_sum(Rs0, RSum),
        maplist(divide(RSum), Rs0, Rs),
        first_uniforms(Rest, Us, Draws),
        msort(Draws, Ps),
        walk(Rs, Ps, Extra),
        append(Det, Extra, All),
        msort(All, Is)
    ).

%   first_uniforms(+K, +Us, -First): the first K of Us.
first_uniforms(K, Us, First) :-
    length(First, K),
    (   append(First, _, Us)
    ->  true
    ;   domain_error(enough_uniforms(K), Us)
    ).

%   systematic_positions(+K, +N, +U, -Ps): (U+K)/N, ..., (U+N-1)/N
systematic_positions(N, N, _, []) :- !.
systematic_positions(K, N, U, [P|Ps]) :-
    P is (U + K) / N,
    K1 is K + 1,
    systematic_positions(K1, N, U, Ps).

residual_copies(N, W, C) :-
    C is floor(N * W).

residual_weight(N, W, C, R) :-
    R is N * W - C.

divide(D, X, Y) :-
    Y is X / D.

repeat_index(I, C, L0, L) :-
    length(Is, C),
    maplist(=(I), Is),
    append(Is, L, L0).

%   walk(+Weights, +SortedPositions, -Indices): for each position the first
%   index whose cumulative weight exceeds it; the last index for a position
%   that none exceeds (as if the last cumulative weight were 1 and positions
%   below 1).
walk(Ws, Ps, Is) :-
    length(Ws, N),
    Last is N - 1,
    walk(Ps, Ws, 0, 0.0, Last, Is).

%   walk(+Ps, +Ws, +I, +C0, +Last, -Is): Ws the weights from index I on, C0
%   the cumulative weight before I.
walk([], _, _, _, _, []).
walk([P|Ps], Ws, I, C0, Last, Is) :-
    (   I =:= Last
    ->  last_index([P|Ps], Last, Is)
    ;   Ws = [W|Ws1],
        C is C0 + W,
        (   C > P
        ->  Is = [I|Is1],
            walk(Ps, Ws, I, C0, Last, Is1)
        ;   I1 is I + 1,
            walk([P|Ps], Ws1, I1, C, Last, Is)
        )
    ).

last_index([], _, []).
last_index([_|Ps], Last, [Last|Is]) :-
    last_index(Ps, Last, Is).

%!  resample_preserving(+LogWeights:list(float), +Strata:list(integer), +Keep:integer,
%!                      +Uniforms:list(float), -Indices:list(integer),
%!                      -LogWeights1:list(float)) is det.
%
%   Resampling that keeps every stratum of the particles alive with its mass (the mixture
%   resampling of Vermaak, Doucet and Perez 2003, "Maintaining multi-modality through
%   mixture tracking"): Strata gives each particle a stratum (an integer; the caller's
%   hypotheses: e.g. which of two look-alike objects is which), and each stratum k of mass
%
%       M_k = sum_{i in k} w_i > 0
%
%   is resampled on its own, systematically (the first uniform U, positions (U+j)/n_k among
%   its particles' weights w_i/M_k), to n_k copies, each of weight M_k/n_k: the weighted
%   particles represent the same mixture, but a stratum of small mass (a hypothesis that
%   later evidence may yet confirm) keeps at least Keep particles instead of dying out by
%   the resampling's chance.  The counts: n_k = Keep for every stratum whose share
%   R M_k / M_big of the particles the others leave (R = N - Keep |small|, M_big the mass
%   of the others) is below Keep, found by repetition; the others share R in proportion to
%   their masses, rounded by largest remainders (ties to the lower stratum id).  When there
%   are more strata than N / Keep, Keep is taken as N // K.  Strata of mass 0 get no
%   particles.  Indices (0-based) are ascending, LogWeights1 their normalised log weights.
%
%   @error domain_error(same_length(N), Strata) if Strata and LogWeights differ in length.
%   @error type_error(positive_integer, Keep) if Keep is not one.
resample_preserving(LWs, Strata, Keep, Us, Is, LWs1) :-
    must_be(positive_integer, Keep),
    must_be(list(integer), Strata),
    length(LWs, N),
    (   length(Strata, N) -> true ; domain_error(same_length(N), Strata) ),
    first_uniforms(1, Us, [U]),
    weights_normalised(LWs, Ws),
    numlist(0, N, [_|Ids1]),
    maplist(minus_one, Ids1, Ids),
    foldl(stratum_member, Strata, Ws, Ids, [], Tagged0),
    msort(Tagged0, Tagged),                         % by stratum, then index
    group_pairs_by_key(Tagged, Groups0),
    include(positive_mass, Groups0, Groups),
    length(Groups, K),
    Keep1 is max(1, min(Keep, N // max(K, 1))),
    maplist(group_mass, Groups, Masses),
    stratum_counts(Masses, N, Keep1, Counts),
    foldl(resample_stratum(U), Groups, Masses, Counts, Pairs, []),
    msort(Pairs, Sorted),
    pairs_keys_values(Sorted, Is, LWs1).

minus_one(I1, I) :- I is I1 - 1.

%   stratum_member(+S, +W, +I, +T0, -T): T0 with S-(I-W) added (a weight-0 particle too:
%   its stratum may have mass elsewhere).
stratum_member(S, W, I, T0, [S-(I-W)|T0]).

positive_mass(_-Members) :-
    group_mass(_-Members, M),
    M > 0.

group_mass(_-Members, M) :-
    pairs_values(Members, Ws),
    sum_list(Ws, M).

%   stratum_counts(+Masses, +N, +Keep, -Counts): the n_k of resample_preserving/6.
stratum_counts(Masses, N, Keep, Counts) :-
    length(Masses, K),
    length(Small0, K),
    maplist(=(false), Small0),
    small_strata(Masses, N, Keep, Small0, Small),
    counts_given_small(Masses, Small, N, Keep, Counts).

small_strata(Masses, N, Keep, Small0, Small) :-
    share_of_rest(Masses, Small0, N, Keep, Shares),
    maplist(mark_small(Keep), Small0, Shares, Small1),
    (   Small1 == Small0
    ->  Small = Small0
    ;   small_strata(Masses, N, Keep, Small1, Small)
    ).

mark_small(_, true, _, true) :- !.
mark_small(Keep, false, Share, Small) :-
    (   Share < Keep -> Small = true ; Small = false ).

%   share_of_rest(+Masses, +Small, +N, +Keep, -Shares): R M_k / M_big for the strata not
%   small (0 for the small ones).
share_of_rest(Masses, Small, N, Keep, Shares) :-
    foldl(big_mass, Masses, Small, 0.0, Big),
    include(==(true), Small, Smalls),
    length(Smalls, S),
    R is N - Keep * S,
    maplist(share(R, Big), Masses, Small, Shares).

big_mass(M, false, B0, B) :- !, B is B0 + M.
big_mass(_, true, B, B).

share(_, _, _, true, 0.0) :- !.
share(R, Big, M, false, Share) :-
    (   Big > 0 -> Share is R * M / Big ; Share = 0.0 ).

counts_given_small(Masses, Small, N, Keep, Counts) :-
    share_of_rest(Masses, Small, N, Keep, Shares),
    maplist(floor_count(Keep), Small, Shares, Floors),
    sum_list(Floors, Given),
    Left is N - Given,
    length(Masses, K),
    numlist(1, K, Ks),
    remainder_keys(Small, Shares, Floors, Ks, Keyed),
    keysort(Keyed, ByRemainder),
    pairs_values(ByRemainder, Order),
    length(Extra, Left),
    append(Extra, _, Order),
    maplist(add_extra(Extra), Ks, Floors, Counts).

floor_count(Keep, true, _, Keep) :- !.
floor_count(_, false, Share, F) :- F is floor(Share).

%   remainder_keys(+Small, +Shares, +Floors, +Ks, -Keyed): -Remainder-K per stratum, so that
%   keysort/2 puts the largest remainders first (a small stratum's counts as none).
remainder_keys([], [], [], [], []).
remainder_keys([S|Ss], [Sh|Shs], [F|Fs], [K|Ks], [Key-K|Keyed]) :-
    (   S == true -> Key = 2.0 ; Key is -(Sh - F) ),
    remainder_keys(Ss, Shs, Fs, Ks, Keyed).

add_extra(Extra, K, F, C) :-
    (   memberchk(K, Extra) -> C is F + 1 ; C = F ).

%   resample_stratum(+U, +Group, +Mass, +Count, -Pairs, ?Tail): Count systematic copies of
%   the stratum's particles, each Index-LogWeight with weight Mass/Count.
resample_stratum(_, _, _, 0, Pairs, Pairs) :- !.
resample_stratum(U, _-Members, M, Count, Pairs, Tail) :-
    pairs_keys_values(Members, Ids, Ws0),
    maplist(divide(M), Ws0, Ws),
    systematic_positions(0, Count, U, Ps),
    walk(Ws, Ps, Local),
    L is log(M / Count),
    Array =.. [ids|Ids],
    foldl(copy_of(Array, L), Local, Pairs, Tail).

copy_of(Array, L, J, [I-L|T], T) :-
    J1 is J + 1,
    arg(J1, Array, I).

%!  numpy_sum(+Xs:list(float), -Sum:float) is det.
%
%   The sum of the non-empty list Xs by pairwise summation, as numpy sums a
%   float64 array, bit for bit.  A run of fewer than 8 numbers is added
%   from left to right; a run of at most 128 in 8 interleaved partial sums
%   (the k-th takes elements k, k+8, ...), combined as
%   ((s0+s1)+(s2+s3))+((s4+s5)+(s6+s7)), then the N mod 8 left over added
%   one by one; a longer run is split in two, the first half floor(N/2)
%   rounded down to a multiple of 8, and the halves' sums added.  (For
%   non-negative numbers, as the residuals are: numpy starts from -0.0,
%   the same as starting from the first number.)
numpy_sum(Xs, S) :-
    length(Xs, N),
    pairwise_sum(N, Xs, [], S).

%   pairwise_sum(+N, +Xs, -Rest, -S): S the sum of the first N of Xs, Rest
%   the others.
pairwise_sum(N, [X|Xs], Rest, S) :-
    N < 8, !,
    N1 is N - 1,
    add_run(N1, Xs, X, S, Rest).
pairwise_sum(N, [X0,X1,X2,X3,X4,X5,X6,X7|Xs], Rest, S) :-
    N =< 128, !,
    Blocks is N // 8 - 1,
    add_blocks(Blocks, Xs, s(X0,X1,X2,X3,X4,X5,X6,X7), s(R0,R1,R2,R3,R4,R5,R6,R7), Xs1),
    S0 is ((R0+R1)+(R2+R3))+((R4+R5)+(R6+R7)),
    K is N mod 8,
    add_run(K, Xs1, S0, S, Rest).
pairwise_sum(N, Xs, Rest, S) :-
    Half is N // 2,
    N1 is Half - Half mod 8,
    N2 is N - N1,
    pairwise_sum(N1, Xs, Xs1, S1),
    pairwise_sum(N2, Xs1, Rest, S2),
    S is S1 + S2.

%   add_run(+K, +Xs, +S0, -S, -Rest): S0 plus the first K of Xs, left to right.
add_run(0, Xs, S, S, Xs) :- !.
add_run(K, [X|Xs], S0, S, Rest) :-
    S1 is S0 + X,
    K1 is K - 1,
    add_run(K1, Xs, S1, S, Rest).

add_blocks(0, Xs, R, R, Xs) :- !.
add_blocks(B, [X0,X1,X2,X3,X4,X5,X6,X7|Xs], s(A0,A1,A2,A3,A4,A5,A6,A7), R, Rest) :-
    B0 is A0+X0, B1 is A1+X1, B2 is A2+X2, B3 is A3+X3,
    B4 is A4+X4, B5 is A5+X5, B6 is A6+X6, B7 is A7+X7,
    B1s is B - 1,
    add_blocks(B1s, Xs, s(B0,B1,B2,B3,B4,B5,B6,B7), R, Rest).
