% Follow the occluder: a theory of occlusion of the paper's shape (section 2.3) for two
% objects, a ball and a box.  While an object is seen, its position is a slow random walk
% weighted by the observed position.  When an object that was seen at t is not seen at t+1,
% every seen object above it and within 0.3 m (in the table plane) is a potential occluder
% and one of them is chosen uniformly; from then on the hidden object keeps its offset to
% its occluder, so it moves with it.  When no occluder is near, a hidden object stays put.
%
% Per frame: observed(O) for each object seen, and observation(pos(O)) ~= (X,Y,Z) for its
% position (metres).  Query e.g.  occluded_by(ball_1, box_1):t  or  pos(ball_1):t.

:- dynamic(observed/1).          % a fact of each step (the filter's actions / facts)

object(ball_1) := true.
object(box_1) := true.

start(ball_1, (0.0, 0.0, 0.02)) := true.
start(box_1, (0.05, 0.0, 0.12)) := true.

process_cov([0.0001, 0, 0, 0, 0.0001, 0, 0, 0, 0.0001]) := true.   % 1 cm per step
sensor_cov([0.0004, 0, 0, 0, 0.0004, 0, 0, 0, 0.0004]) := true.    % 2 cm

% Time 0: where the objects start; everything is seen, nothing is hidden.
pos(O):0 ~ gaussian([X, Y, Z], C) := start(O, (X, Y, Z)), process_cov(C).
seen(O):0 ~ val(true) := object(O).
hidden_under(O):0 ~ val(none) := object(O).

% What the frame says is seen.
seen(O):t+1 ~ val(true) := object(O), observed(O).
seen(O):t+1 ~ val(false) := object(O), \+ observed(O).

% A potential occluder of O: O was seen and now is not; H is seen, above O and near it.
occluder(O, H):t+1 :=
    seen(O):t ~= true, seen(O):t+1 ~= false,
    object(H), H \== O, seen(H):t+1 ~= true,
    pos(O):t ~= (X, Y, Z), pos(H):t+1 ~= (XH, YH, ZH),
    D is sqrt((X - XH)**2 + (Y - YH)**2), Z < ZH, D < 0.3.

% Which one it is hidden under (none: not hidden, or hidden with no occluder near).
hidden_under(O):t+1 ~ uniform(Hs) :=
    object(O), seen(O):t ~= true, seen(O):t+1 ~= false,
    findall_forward(H, occluder(O, H):t+1, Hs), Hs \== [].
hidden_under(O):t+1 ~ val(none) :=
    object(O), seen(O):t ~= true, seen(O):t+1 ~= false,
    findall_forward(H, occluder(O, H):t+1, []).
hidden_under(O):t+1 ~ val(H) :=
    object(O), seen(O):t ~= false, seen(O):t+1 ~= false, hidden_under(O):t ~= H.
hidden_under(O):t+1 ~ val(none) := object(O), seen(O):t+1 ~= true.

occluded_by(O, H):t := hidden_under(O):t ~= H, H \== none.

% Positions.
pos(O):t+1 ~ gaussian([X, Y, Z], C) :=
    object(O), seen(O):t+1 ~= true, pos(O):t ~= (X, Y, Z), process_cov(C).
pos(O):t+1 ~ val((X1, Y1, Z1)) :=
    object(O), seen(O):t+1 ~= false, hidden_under(O):t+1 ~= H, H \== none,
    pos(O):t ~= (X, Y, Z), pos(H):t ~= (HX, HY, HZ), pos(H):t+1 ~= (HX1, HY1, HZ1),
    X1 is X + HX1 - HX, Y1 is Y + HY1 - HY, Z1 is Z + HZ1 - HZ.
pos(O):t+1 ~ val(P) :=
    object(O), seen(O):t+1 ~= false, hidden_under(O):t+1 ~= none, pos(O):t ~= P.

observation(pos(O)):t+1 ~ gaussian([X, Y, Z], C) := pos(O):t+1 ~= (X, Y, Z), sensor_cov(C).
