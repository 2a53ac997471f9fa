% The original DC tutorial, restated: a coin, a colour, a number of balls,
% and an urn from which a ball is drawn.
coin ~ finite([0.2:true, 0.8:false]).
color ~ finite([0.1:black, 0.5:red, 0.4:blue]).
nballs ~ uniform(1:10).
ball(X) := nballs ~= N, between(1, N, X).
material(X) ~ finite([0.3:wood, 0.7:metal]) := ball(X).
color(X) ~ uniform([grey, blue, black]) := material(X) ~= metal.
color(X) ~ uniform([black, brown]) := material(X) ~= wood.
drawn(_) ~ uniform(Balls) := nballs ~= N, findall(X, between(1, N, X), Balls).
size(X) ~ beta(2, 3) := material(X) ~= metal.
size(X) ~ beta(4, 2) := material(X) ~= wood.
