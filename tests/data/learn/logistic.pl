% Generator of the recovery test "logistic on a continuous feature" (tests/test_learn_recovery.py),
% the paper's occluder clause (section 4, Figure 5).
%
% Groundings are pairs (A, O), e.g. (a1, o1) (any key: the priors have no body). Features:
%     d(A, O):t ~ uniform(0, 0.3)            continuous, the distance at t;
%     observed(A):t+1                        holds with probability 0.3 (seen(A):t+1 = true).
% The target occluder(A, O):t+1 in {true, false}:
%     observed(A):t+1      -> false (an object that is seen is not occluded);
%     otherwise            -> P(true) = sigmoid(-16.9 * d(A, O):t + 0.8), the paper's weights.
% evaluate/2 scores the two clauses of occluder on data with the facts of d and observed.

d(A, O):t ~ uniform(0, 0.3).
seen(A):t ~ finite([0.3:true, 0.7:false]).
observed(A):t := seen(A):t ~= true.

occluder(A, O):t+1 ~ finite([0.0:true, 1.0:false]) :=
    observed(A):t+1.
occluder(A, O):t+1 ~ finite([P1:true, P2:false]) :=
    \+ observed(A):t+1,
    d(A, O):t ~= D,
    logistic([D], [-16.9, 0.8], P1),
    P2 is 1 - P1.
