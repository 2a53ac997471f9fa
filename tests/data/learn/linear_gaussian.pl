% Generator of the recovery test "linear-Gaussian" (tests/test_learn_recovery.py).
%
% Entities e1, e2, ... (any key: the priors have no body). Two independent features:
%     x(X) ~ uniform(0, 1)                 continuous, the regressor of y's mean;
%     z(X) in {u, v}, uniform              discrete, irrelevant (no clause of y reads it).
% The target is a linear-Gaussian of x, weight 2.0, bias 0.5, variance 0.04 (sd 0.2):
%     y(X) ~ gaussian(2.0*x(X) + 0.5, 0.04).
% evaluate/2 scores the clause of y on data that has the facts of x.

x(X) ~ uniform(0, 1).
z(X) ~ finite([0.5:u, 0.5:v]).

y(X) ~ gaussian(2.0*V + 0.5, 0.04) := x(X) ~= V.
