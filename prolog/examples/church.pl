% Examples in the style of the Church tutorial (the original's church-dc.pl),
% restated.
coin ~ finite([0.5:true, 0.5:false]).
trickcoin ~ finite([0.95:h, 0.05:t]).

fair-coin ~ finite([0.5:true, 0.5:false]).
bent-coin ~ finite([0.7:h, 0.3:t]) := fair-coin ~= false.
bent-coin ~ finite([0.1:h, 0.9:t]) := fair-coin ~= true.

lung-cancer(_) ~ finite([0.01:true, 0.99:false]).
cold(_) ~ finite([0.2:true, 0.8:false]).
cough(P) := lung-cancer(P) ~= true.
cough(P) := cold(P) ~= true.

breast_cancer ~ finite([0.01:true, 0.99:false]).
positive_mammogram ~ finite([0.8:true, 0.2:false]) := breast_cancer ~= true.
positive_mammogram ~ finite([0.096:true, 0.904:false]) := breast_cancer ~= false.

% conditional: d = a + b + c
a ~ finite([0.1:1, 0.9:0]).
b ~ finite([0.1:1, 0.9:0]).
c ~ finite([0.1:1, 0.9:0]).
d ~ val(D) := a ~= A, b ~= B, c ~= C, D is A + B + C.

% noisy-or medical diagnosis with non-memoised flips true(P)
lung_cancer := true(0.01).
tb := true(0.005).
cold := true(0.2).
stomach_flu := true(0.1).
other := true(0.1).
cough := cold, true(0.5).
cough := lung_cancer, true(0.3).
cough := tb, true(0.7).
cough := other, true(0.01).
fever := cold, true(0.3).
fever := stomach_flu, true(0.5).
fever := tb, true(0.2).
fever := other, true(0.01).
chest_pain := lung_cancer, true(0.4).
chest_pain := tb, true(0.5).
chest_pain := other, true(0.01).
shortness_of_breath := lung_cancer, true(0.4).
shortness_of_breath := tb, true(0.5).
shortness_of_breath := other, true(0.01).
