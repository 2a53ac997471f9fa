% The generator of occluder.pl: before/after states of object pairs (A, O) as the paper's
% learned theory of occlusion describes them (section 4, example 4 and Figure 5).
%
%   occluded_by(A, O):t        A was hidden by O in the previous frame (40 % of the pairs)
%   observed(A):t+1            A is seen in the next frame (30 %)
%   distance(A, O):t           their distance in the table plane, uniform on [0, 0.4] m
%   occluder(A, O):t+1         O hides A in the next frame:
%       seen at t+1: never; hidden by O before and not seen: 0.92;
%       else the paper's logistic on the distance, P1 = sigmoid(0.8 - 16.9 D).
%
% Sampled with probanchor.ddclearn.synthetic.sample_data (see occluder.pl's header).

hid(A, O):t ~ finite([0.4:true, 0.6:false]).
occluded_by(A, O):t := hid(A, O):t ~= true.
seen(A):t+1 ~ finite([0.3:true, 0.7:false]).
observed(A):t+1 := seen(A):t+1 ~= true.
distance(A, O):t ~ uniform(0, 0.4).

occluder(A, O):t+1 ~ finite([0.0:true, 1.0:false]) :=
    observed(A):t+1.
occluder(A, O):t+1 ~ finite([0.92:true, 0.08:false]) :=
    \+ observed(A):t+1, occluded_by(A, O):t.
occluder(A, O):t+1 ~ finite([P1:true, P2:false]) :=
    \+ observed(A):t+1, \+ occluded_by(A, O):t,
    distance(A, O):t ~= D, logistic([D], [-16.9, 0.8], P1), P2 is 1 - P1.
