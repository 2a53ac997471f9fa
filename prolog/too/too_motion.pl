/*  too_motion.pl -- the hand-written rules of carrying and of the motion of hidden objects.

    Included by too.pl and by the theories `anchoring learn-theory` writes, after the
    occlusion rules: the transitive clause, the carriers' rules (a hand picks an object up and
    carries it until it lets go: when it does is too_release.pl's in too.pl, learned in a
    learned theory), where a hidden object is (with its occluder, in place, coasting) and the
    variance of where an object reappears.  These rules are structure (the
    vocabulary and frame of carrying and of motion); the constants they read are
    too_parameters.pl's in too.pl and fitted from the data in a learned theory.
*/

% Transitive occlusion (section 5.3 of the paper; remove this clause to switch it off): an
% object whose occluder is itself hidden stays with it, under whatever hides the occluder (or,
% while the occluder is under nothing, where the occluder is believed to be: a box lowered
% over a mug hides the mug a few frames before it covers it).
occluded_by(A, O):t+1 :=
    occluded_by(A, O):t, hidden(A):t+1, hidden(O):t+1.

% ------------------------------------------------------------------ carriers
% A hand (a carrier) picks an object up by closing over it, carries it in 3-D and puts it
% down.  These rules are background knowledge, kept beside learned occlusion rules (as the
% affordances and the transitive clause are).  A carrier's position is where it closes (the
% runner gives a hand's grip point), so what it holds is near it, however much of the
% forearm is in view.
% (Every rule starts with the carriers, `object(O), is_carrier(O)` or `hand_known`: with no
% hand in the scene they cost nothing; and none reads a derived predicate at t other than
% seen/1 and occluded_by/2, which the filter keeps anyway: rest_z/1 and raised/1 are variables
% of the objects a hand holds.)
% O's grip is over the hidden A: within grip_reach of where A was in the table plane, at most
% grip_height above A's top and not below its centre (grip_was_over/2: so it was in the
% previous frame).  A's top is half its kind's height above its centre (kind_height/2, in a
% learned theory; without it, the grip is measured from A's centre).
grip_over(O, A):t+1 :=
    object(O), is_carrier(O), observed(O), hidden(A):t+1, O \== A, can_be_occluded(A),
    pos(A):t ~= (X, Y, Z), pos(O):t+1 ~= (XO, YO, ZO),
    grip_reach(R), grip_height(H), occluder_rise(L), top_gap(A, G),
    D is sqrt((X-XO)**2 + (Y-YO)**2), D < R, ZO - Z - G < H, Z < ZO + L.
grip_was_over(O, A):t+1 :=
    object(O), is_carrier(O), seen(O):t, object(A), A \== O, \+ seen(A):t,
    can_be_occluded(A), pos(A):t ~= (X, Y, Z), pos(O):t ~= (XO, YO, ZO),
    grip_reach(R), grip_height(H), occluder_rise(L), top_gap(A, G),
    D is sqrt((X-XO)**2 + (Y-YO)**2), D < R, ZO - Z - G < H, Z < ZO + L.
top_gap(A, G) := category(A, C), kind_height(C, H), G is H / 2.
top_gap(A, 0.0) := category(A, C), \+ kind_height(C, _).
% O, holding nothing else, may have picked A up when A vanished just now under its grip, or
% when its grip has just come over A (it was not in the previous frame): a candidate occluder,
% picked as any other by the occlusion rules above (hand-written or learned).  A hand hovering
% over what it has just let go of does not pick it up again.
grasp_candidate(A, O):t+1 :=
    grip_over(O, A):t+1, \+ occluded_by(_, O):t,
    (seen(A):t -> true ; \+ grip_was_over(O, A):t+1).
% O has picked A up when it rises from over A and A stays unseen: left on the table, A would be
% in view once the hand is off it (a particle that had A stay `behind` when it vanished under
% the hand).  Not what a hand has let go of (it has rest_z/1 since).
grasp_candidate(A, O):t+1 :=
    grip_was_over(O, A):t+1, observed(O), hidden(A):t+1, \+ occluded_by(A, _):t,
    \+ occluded_by(_, O):t, \+ rest_z(A):t ~= _,
    pos(O):t ~= (_, _, Z0), pos(O):t+1 ~= (_, _, Z1), grip_rise(E), Z1 > Z0 + E.
occluder_candidate(A, O):t+1 := hand_known, grasp_candidate(A, O):t+1.

% The carrier holds A while it is perceived (and, by the transitive clause, while it is not)
% until it lets A go.
occluded_by(A, O):t+1 :=
    object(O), is_carrier(O), occluded_by(A, O):t, hidden(A):t+1, observed(O),
    \+ released(A):t+1 ~= true.
% Where A stood when a hand took it (its height): a carried object is not lowered below it;
% kept while A is hidden.
rest_z(A):t+1 ~ val(Z) :=
    object(O), is_carrier(O), occluded_by(A, O):t+1, \+ occluded_by(A, O):t,
    pos(A):t ~= (_, _, Z).
rest_z(A):t+1 ~ val(Z) :=
    hand_known, hidden(A):t+1, rest_z(A):t ~= Z,
    \+ (object(O), is_carrier(O), occluded_by(A, O):t+1, \+ occluded_by(A, O):t).
% When the hand lets go of A (released(A):t+1 ~= true, drawn while it holds A: the carrier
% is perceived and A hidden) is too/too_release.pl's rule in too.pl and a tree learned from the
% carries in a learned theory (its vocabulary in too/too_learned_glue.pl).

% ------------------------------------------------------------------ positions of hidden objects
% Hidden under the same occluder as before: moves with it (in the table plane; a carrier
% such as a hand also lifts it, and lowers it no further than where it stood: a hand closing
% over an object comes down to it, then lifts it).  Its offset from the occluder's centre is
% kept with follow_keep and jittered with follow_var, so the belief settles within the
% occluder's footprint (spread sqrt(follow_var / (1 - follow_keep^2)), 6 mm) instead of
% wandering further off frame after frame; its height hardly jitters (an object under a
% container stays on the table).
pos(A):t+1 ~ gaussian([MX, MY, MZ], [V, 0, 0, 0, V, 0, 0, 0, VZ]) :=
    hidden(A):t+1, occluded_by(A, O):t, occluded_by(A, O):t+1,
    pos(O):t ~= (X0, Y0, Z0), pos(O):t+1 ~= (X1, Y1, Z1), pos(A):t ~= (X, Y, Z),
    follow_keep(K), MX is X1 + K*(X - X0), MY is Y1 + K*(Y - Y0),
    (   is_carrier(O)
    ->  MZ0 is Z + Z1 - Z0,
        (   rest_z(A):t+1 ~= R
        ->  MZ is max(MZ0, R)
        ;   MZ = MZ0
        )
    ;   MZ = Z
    ),
    follow_var(V), height_spread(V, VZ).
% Hidden under an occluder that has just been picked: under it, at the object's own height
% (in a hand that picked it up late, as it was already rising: at most grip_drop below the
% grip).
pos(A):t+1 ~ gaussian([XO, YO, Z], C) :=
    hidden(A):t+1, occluded_by(A, O):t+1, \+ occluded_by(A, O):t,
    pos(O):t+1 ~= (XO, YO, ZO), pos(A):t ~= (_, _, Z0),
    (   is_carrier(O)
    ->  grip_drop(G), Z is max(Z0, ZO - G)
    ;   Z = Z0
    ),
    follow_var(V), diagonal(V, C).
% Hidden under nothing (behind something, or left on the table): it may be moved while unseen
% (a mug carried behind a box, a container swapped while merged with another in the image).
% It coasts on with the velocity it had when it vanished, slowing down (coast_keep per frame,
% so at most 1 / (1 - coast_keep) frames' worth of its last motion: a static object stays),
% and its belief spreads per frame in the table plane by wander_var if it was moving as it
% vanished (at moving_speed or faster), else by rest_var (spread/2 below: an object standing
% still behind something stays where it stood); a reappearance then weights the particles by
% where they had it, and matching finds the particles near it.  One a
% hand has let go of (it has rest_z/1) is on the table, at the height it stood at: a hand may
% let go a centimetre or two above it, and an object left in the air would be under the grip
% again as the hand rises, which would take it again.
pos(A):t+1 ~ gaussian([MX, MY, MZ], [V, 0, 0, 0, V, 0, 0, 0, VZ]) :=
    hidden(A):t+1, \+ is_carrier(A), \+ occluded_by(A, _):t+1, pos(A):t ~= (X, Y, Z),
    velocity(A, VX, VY):t+1, MX is X + VX, MY is Y + VY,
    (   hand_known, rest_z(A):t+1 ~= R
    ->  MZ = R
    ;   MZ = Z
    ),
    spread(A, V):t+1, height_spread(V, VZ).
% A hidden object under nothing coasts while it has been since it vanished moving (as fast as
% moving_speed or faster then); it rests otherwise.
coasting(A):t+1 :=
    hidden(A):t+1, seen(A):t, vel(A):t ~= (VX, VY), moving_speed(S), VX*VX + VY*VY >= S*S.
coasting(A):t+1 := coasting(A):t, hidden(A):t+1, \+ occluded_by(A, _):t+1.
spread(A, V):t+1 := coasting(A):t+1, wander_var(V).
spread(A, V):t+1 := object(A), \+ coasting(A):t+1, resting_var(V).
% A theory written before rest_var/1 (a learned theory of an older version, loaded with a
% warning that names it) spreads every hidden object by wander_var, as it did then.
resting_var(V) := rest_var(V).
resting_var(V) := \+ rest_var(_), wander_var(V).
% A hidden object's height (it stays on the table, or in the hand that holds it) spreads by
% height_var, fitted from the data in a learned theory; too.pl has none and spreads it by a
% hundredth of its spread in the table plane V (height_var/1 is declared in too_base.pl).
height_spread(_, VZ) := height_var(VZ).
height_spread(V, VZ) := \+ height_var(_), VZ is V / 100.
% A hand out of view is believed where it was last seen, the same point in every particle, so
% that when it comes back its position weighs every particle alike (a hand's position says
% nothing about what hides what).
pos(A):t+1 ~ val((X, Y, Z)) := hidden(A):t+1, is_carrier(A), pos(A):t ~= (X, Y, Z).

% The velocity of a hidden object under nothing: the last one, slowing down; else none.
vel(A):t+1 ~ val((VX, VY)) :=
    hidden(A):t+1, \+ occluded_by(A, _):t+1, velocity(A, VX, VY):t+1.
velocity(A, VX, VY):t+1 :=
    vel(A):t ~= (VX0, VY0), coast_keep(K), VX is K * VX0, VY is K * VY0.
velocity(A, 0.0, 0.0):t+1 := object(A), \+ vel(A):t ~= _.

% The variance of where an object is now around its belief (prior_var/2, read by too_base.pl):
% motion for an object that was perceived in the previous frame, a wider one for an object
% that reappears.
prior_var(A, P):t+1 := object(A), seen(A):t, motion_var(P).
prior_var(A, P):t+1 := object(A), \+ seen(A):t, \+ lost_anywhere(A):t, reappear_var(P).
% An object lost while the camera saw nothing, and not under anything since, may have been moved
% anywhere on the table (two look-alike containers swapped): where it shows up again says little
% about which particle was right, so that the hypotheses of which one is which (the identity
% hypotheses the runner keeps in the particles) survive until something decides them.
prior_var(A, P):t+1 := object(A), \+ seen(A):t, lost_anywhere(A):t, lost_var(P).
