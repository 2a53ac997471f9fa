% A 1-D linear Gaussian model: a random walk observed with Gaussian noise.  Its exact
% filtering distribution is Gaussian and given by the Kalman filter, which the tests compare
% against:
%   x_0 ~ N(0, 1),   x_{t+1} = x_t + w,  w ~ N(0, 0.5),   y_{t+1} = x_{t+1} + v,  v ~ N(0, 1).
% Observations:  observation(y) ~= 0.73

x:0 ~ gaussian(0.0, 1.0).
x:t+1 ~ gaussian(X, 0.5) := x:t ~= X.
observation(y):t+1 ~ gaussian(X, 1.0) := x:t+1 ~= X.
