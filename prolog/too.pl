/*  too.pl -- the theory of occlusion: which object may hide which, and where a hidden object is.

    An ordinary DDC program, filtered over time by the particle filter (prolog/ddc.pl);
    edit it freely.  What the runner tells it at every step t+1 (one camera frame):

      facts         object(A)          every anchor that exists, as an atom (ball-1 -> ball_1)
                    category(A, C)     its best category: ball, mug, cup, box, can, skin, ...
                    observed(A)        A was perceived in this frame
      observations  observation(pos(A)) ~= (X,Y,Z)   its perceived position (metres, z up);
                                                      a hand's (a carrier's) is where it
                                                      closes: its percept's grip point

    What it reads back, per particle: pos(A):t ~= (X,Y,Z) and occluded_by(A, O):t.
*/

% ------------------------------------------------------------------ facts
% What the runner asserts at every step (above): declared, so that reading them is not taken
% for a call to a predicate defined nowhere.
:- dynamic((object/1, category/2, observed/1)).

% ------------------------------------------------------------------ parameters
% Variances are per axis, in square metres; one step is one camera frame.
obs_var(0.0001).            % measurement noise of a perceived position: (1 cm)^2
motion_var(0.0004).         % how far a perceived object moves in one frame: (2 cm)^2
reappear_var(0.0025).       % where a hidden object shows up again, around its belief: (5 cm)^2
lost_var(0.09).             % where an object lost while the camera saw nothing shows up again:
                            % (30 cm)^2 around its belief (it may have been moved anywhere)
follow_var(0.000004).       % jitter of a hidden object that follows its occluder: (2 mm)^2
wander_var(0.0001).         % how far a hidden object under nothing may move in a frame: (1 cm)^2
coast_keep(0.9).            % fraction of its velocity a hidden object under nothing keeps per frame
follow_keep(0.95).          % fraction of its offset from the occluder's centre kept per frame
occluder_reach(0.15).       % an occluder is within 15 cm of the object in the table plane ...
occluder_rise(0.02).        % ... and its centre is no more than 2 cm lower than the object's
lowering_speed(0.003).      % an occluder coming down sinks by more than this per frame (m) ...
lowered_reach(0.05).        % ... onto an object within this distance in the table plane (m)
behind_when_covered(0.1).   % the probability that an object vanishing as an occluder comes down
                            % onto it is hidden by something else
cover_height(0.12).         % a container whose centre rises more than this above the object's
                            % centre no longer covers it (it was lifted)
grip_reach(0.06).           % a carrier (a hand) closes over an object within 6 cm of where it
grip_height(0.1).           % grips in the table plane, its grip at most 10 cm above the object
lift_margin(0.03).          % a carried object lifted 3 cm above where it stood was picked up ...
release_margin(0.02).       % ... and is put down when carried back within 2 cm of that height,
release_p(0.6).             % ... where the hand lets go of it with this probability per frame
grip_drop(0.02).            % what a hand holds is about 2 cm below its grip point
grip_rise(0.01).            % a hand rises when its grip goes up more than 1 cm in a frame

% ------------------------------------------------------------------ background knowledge
% Affordances (anchoring learn-theory keeps them beside the learned rules, as the paper's
% experiments keep them, section 5.2).
% What cannot hide anything: a ball does not afford occluding, nor does a can (closed, it
% stands upright and contains nothing that could be put under it).
cannot_occlude(ball) := true.
cannot_occlude(can) := true.
% What cannot be hidden by other objects: hands (skin) are not anchored inside anything.
cannot_be_occluded(skin) := true.
cannot_be_occluded(hand) := true.
% What carries what it hides through space (a hand lifts a grasped object); containers slide
% over the table and what they cover stays on the table.
carrier(skin) := true.
carrier(hand) := true.

% A carrier does not cover things as a container does: it closes over them and carries them
% (the carriers' rules below, kept beside learned occlusion rules as the affordances are).
can_occlude(O) := category(O, C), \+ cannot_occlude(C), \+ carrier(C).
is_carrier(O) := category(O, C), carrier(C).
hand_known := object(O), is_carrier(O).
can_be_occluded(A) := category(A, C), \+ cannot_be_occluded(C).

% ------------------------------------------------------------------ seen and hidden
seen(A):t+1 := observed(A).
hidden(A):t+1 := object(A), \+ observed(A).
% The camera saw nothing at all (covered by a hand): an object lost now could be anywhere.
blind:t+1 := \+ observed(_).

% -- begin hand-written occlusion rules (anchoring learn-theory replaces them with learned ones)
% A container covers an object while its centre is not lifted far above the object's (a
% carrier holds what it holds: the carriers' rules below).
covers(O, A):t+1 :=
    category(O, C), \+ carrier(C), A \== O,
    pos(O):t+1 ~= (_, _, ZO), pos(A):t ~= (_, _, Z), cover_height(H), ZO < Z + H.
% -- end hand-written occlusion rules

% An object hidden while blind stays "lost anywhere" until an occluder explains it.
lost_anywhere(A):t+1 := hidden(A):t+1, blind:t+1, \+ occluded_by(A, _):t+1.
lost_anywhere(A):t+1 := lost_anywhere(A):t, hidden(A):t+1, \+ occluded_by(A, _):t+1.

% ------------------------------------------------------------------ occlusion
% -- begin hand-written occlusion rules (anchoring learn-theory replaces them with learned ones)
% O could hide A: O is perceived now, may occlude, covers A, and is near A's last position
% and not below it, or A was lost while the camera was blind (then every occluder on the
% table could).
occluder_candidate(A, O):t+1 :=
    hidden(A):t+1, can_be_occluded(A),
    observed(O), O \== A, can_occlude(O), covers(O, A):t+1,
    pos(A):t ~= (X, Y, Z), pos(O):t+1 ~= (XO, YO, ZO),
    (   lost_anywhere(A):t
    ->  true
    ;   occluder_reach(R), occluder_rise(H),
        D is sqrt((X-XO)**2 + (Y-YO)**2), D < R, Z < ZO + H
    ).

% What a particle may pick when A is hidden and under nothing:
% - A vanished just now: one of the candidates, or `behind`: A stays where it was, hidden from
%   the camera's view by something in front of it (a container carried or swapped past it,
%   two containers merged into one segment for a few frames) or missed by perception.  Without
%   that choice every particle would put a mug that vanished while another container passed
%   in front of it under that container, and the mug, seen again where it was, would be a new
%   anchor.
% - A was lost while the camera was blind: any covering occluder on the table (its old place
%   says nothing: it was moved unseen).
% - A has been hidden under nothing (behind something, or left on the table when its container
%   was lifted away, or no occluder was near when it vanished): only an occluder that is
%   lowered over it, i.e. covers it now and did not in the previous frame (a box that was
%   still too high when the mug under it vanished; a container put back over an object), or
%   one coming down onto it (below; a cup held over a ball hides it from the camera before it
%   is put down on it).  A container sliding on the table does not slide over what stands
%   there.
lowered_over(O, A):t+1 :=
    occluder_candidate(A, O):t+1, pos(A):t ~= (_, _, Z), cover_height(H),
    (   pos(O):t ~= (_, _, ZO)
    ->  ZO >= Z + H
    ;   true
    ).
% A hand that has just come to close over A (the carriers' rules below).
lowered_over(O, A):t+1 := hand_known, grasp_candidate(A, O):t+1.

% - A vanished just now as an occluder came down onto it (its centre sank by more than
%   lowering_speed since the previous frame and is within lowered_reach of A in the table
%   plane: a container put over it, a hand closing on it): under it, or `behind` with
%   behind_when_covered (the others share the rest).  An occluder passing by, or standing
%   beside A, leaves `behind` as likely as each candidate.
coming_down_on(O, A):t+1 :=
    occluder_candidate(A, O):t+1, pos(A):t ~= (X, Y, _),
    pos(O):t ~= (_, _, Z0), pos(O):t+1 ~= (XO, YO, Z1), lowering_speed(V), Z1 < Z0 - V,
    lowered_reach(R), D is sqrt((X-XO)**2 + (Y-YO)**2), D < R.

% Each particle picks among the choices (the paper's sample_occluder, plus `behind`),
% uniformly but for an occluder coming down onto A.  (In these bodies and in pos/1's, the goals every particle agrees on, such as
% seen(A):t, come before those a particle holds on its own, such as occluded_by(A, _):t:
% the same answers, fewer proofs per particle.)
pick_occluder(A):t+1 ~ uniform(Os) :=
    hidden(A):t+1, lost_anywhere(A):t, \+ occluded_by(A, _):t,
    findall_forward(O, occluder_candidate(A, O):t+1, Os0), sort(Os0, Os), Os \== [].
pick_occluder(A):t+1 ~ finite(Ds) :=
    hidden(A):t+1, seen(A):t, \+ occluded_by(A, _):t,
    findall_forward(O, coming_down_on(O, A):t+1, Os0), sort(Os0, Os1), Os1 \== [],
    behind_or_under(Os1, Ds).
pick_occluder(A):t+1 ~ uniform(Os) :=
    hidden(A):t+1, seen(A):t, \+ occluded_by(A, _):t, \+ coming_down_on(_, A):t+1,
    findall_forward(O, occluder_candidate(A, O):t+1, Os0), sort(Os0, Os1), Os1 \== [],
    Os = [behind | Os1].
pick_occluder(A):t+1 ~ uniform(Os) :=
    hidden(A):t+1, \+ seen(A):t, \+ lost_anywhere(A):t, \+ occluded_by(A, _):t,
    findall_forward(O, lowered_over(O, A):t+1, Os0), sort(Os0, Os), Os \== [].
pick_occluder(A):t+1 ~ finite(Ds) :=
    hidden(A):t+1, \+ seen(A):t, \+ lost_anywhere(A):t, \+ occluded_by(A, _):t,
    \+ lowered_over(_, A):t+1,
    findall_forward(O, coming_down_on(O, A):t+1, Os0), sort(Os0, Os), Os \== [],
    behind_or_under(Os, Ds).

occluded_by(A, O):t+1 := hidden(A):t+1, pick_occluder(A):t+1 ~= O, O \== behind.
% The occlusion lasts while the object is hidden and its occluder is perceived and still
% covers it.
occluded_by(A, O):t+1 := occluded_by(A, O):t, hidden(A):t+1, observed(O), covers(O, A):t+1.
% -- end hand-written occlusion rules
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
% grip_height above A and not below it (grip_was_over/2: so it was in the previous frame).
grip_over(O, A):t+1 :=
    object(O), is_carrier(O), observed(O), hidden(A):t+1, O \== A, can_be_occluded(A),
    pos(A):t ~= (X, Y, Z), pos(O):t+1 ~= (XO, YO, ZO),
    grip_reach(R), grip_height(H), occluder_rise(L),
    D is sqrt((X-XO)**2 + (Y-YO)**2), D < R, ZO - Z < H, Z < ZO + L.
grip_was_over(O, A):t+1 :=
    object(O), is_carrier(O), seen(O):t, object(A), A \== O, \+ seen(A):t,
    can_be_occluded(A), pos(A):t ~= (X, Y, Z), pos(O):t ~= (XO, YO, ZO),
    grip_reach(R), grip_height(H), occluder_rise(L),
    D is sqrt((X-XO)**2 + (Y-YO)**2), D < R, ZO - Z < H, Z < ZO + L.
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
% A has been carried up (the hand rising with it, lift_margin above where it stood) since it
% was taken ...
raised(A):t+1 ~ val(true) :=
    object(O), is_carrier(O), occluded_by(A, O):t+1,
    (   raised(A):t ~= true
    ->  true
    ;   pos(O):t ~= (_, _, ZO0), pos(O):t+1 ~= (_, _, ZO1), ZO1 > ZO0,
        pos(A):t+1 ~= (_, _, Z), rest_z(A):t+1 ~= R, lift_margin(M), Z > R + M
    ).
% ... and carried back down to within release_margin of that height: put down.  The hand lets
% it go with probability release_p per frame there (it stays where it is; the hand leaves).
released(A):t+1 ~ finite([P:true, Q:false]) :=
    object(O), is_carrier(O), occluded_by(A, O):t, observed(O), hidden(A):t+1,
    raised(A):t ~= true, pos(A):t ~= (_, _, Z), rest_z(A):t ~= R, release_margin(M),
    Z =< R + M, release_p(P), Q is 1 - P.

% ------------------------------------------------------------------ positions
% A perceived object's position is the same in every particle: its filtered estimate, a point
% (val) rather than a sample.  One filter carries all objects, so a particle's weight is the
% product of every perceived object's predictive density; were the perceived positions sampled
% per particle (e.g. from the Kalman posterior, the optimal proposal), every frame's weights
% would differ only by those objects' own measurement noise, the effective sample size would
% fall below the threshold nearly every frame, and each resampling would randomly thin the
% modes of hidden objects whose particles carry no information of their own (genetic drift:
% the shell game's ball lost its mode under the right container before it was lifted).  A
% perceived object's posterior hardly depends on which occlusion hypothesis a particle holds,
% so it is marginalised out of the particles (the Rao-Blackwellisation of section 2.2 of the
% paper: keep analytically what needs no sampling); its point is the mean of that Gaussian
% posterior.  Its measurement still weights every particle with the Gaussian predictive
% density below; the density is simply the same in every particle that agrees on where the
% object was, so the weights only move when the particles disagree: when a hidden object is
% seen again, at the positions the particles had believed it to be (the informative event
% that selects the right mode).
% First sighting: at the perceived position.
pos(A):t+1 ~ val((X, Y, Z)) :=
    observed(A), observation(pos(A)) ~= (X, Y, Z), \+ pos(A):t ~= _.
% Perceived in the previous frame too: the mean of the posterior of (motion prior x
% measurement) (a Kalman step with a fixed gain).
pos(A):t+1 ~ val((MX, MY, MZ)) :=
    observed(A), seen(A):t, observation(pos(A)) ~= (OX, OY, OZ), pos(A):t ~= (X, Y, Z),
    prior_var(A, P):t+1, obs_var(R), K is P / (P + R),
    MX is X + K*(OX-X), MY is Y + K*(OY-Y), MZ is Z + K*(OZ-Z).
% Seen again after being hidden: at the perceived position, in every particle (the particle's
% weight already says how well its belief predicted the position; from here on the particles
% agree again).
pos(A):t+1 ~ val((X, Y, Z)) :=
    observed(A), \+ seen(A):t, pos(A):t ~= _, observation(pos(A)) ~= (X, Y, Z).
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
    follow_var(V), VZ is V / 100.
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
% and its belief spreads by wander_var per frame in the table plane; a reappearance then
% weights the particles by where they had it, and matching finds the particles near it.
pos(A):t+1 ~ gaussian([MX, MY, Z], [V, 0, 0, 0, V, 0, 0, 0, VZ]) :=
    hidden(A):t+1, \+ is_carrier(A), \+ occluded_by(A, _):t+1, pos(A):t ~= (X, Y, Z),
    velocity(A, VX, VY):t+1, MX is X + VX, MY is Y + VY,
    wander_var(V), VZ is V / 100.
% A hand out of view is believed where it was last seen, the same point in every particle, so
% that when it comes back its position weighs every particle alike (a hand's position says
% nothing about what hides what).
pos(A):t+1 ~ val((X, Y, Z)) := hidden(A):t+1, is_carrier(A), pos(A):t ~= (X, Y, Z).

% The velocity (metres per frame, in the table plane) of a perceived object: the change of its
% filtered position; of a hidden object under nothing: the last one, slowing down; else none.
vel(A):t+1 ~ val((VX, VY)) :=
    observed(A), seen(A):t, pos(A):t ~= (X0, Y0, _), pos(A):t+1 ~= (X1, Y1, _),
    VX is X1 - X0, VY is Y1 - Y0.
vel(A):t+1 ~ val((VX, VY)) :=
    hidden(A):t+1, \+ occluded_by(A, _):t+1, velocity(A, VX, VY):t+1.
velocity(A, VX, VY):t+1 :=
    vel(A):t ~= (VX0, VY0), coast_keep(K), VX is K * VX0, VY is K * VY0.
velocity(A, 0.0, 0.0):t+1 := object(A), \+ vel(A):t ~= _.

% ------------------------------------------------------------------ observation model
% A perceived position weights each particle by its predictive density: motion + noise for an
% object that was perceived in the previous frame, a wider one for an object that reappears.
observation(pos(A)):t+1 ~ gaussian([X, Y, Z], C) :=
    pos(A):t ~= (X, Y, Z), predictive_var(A, V):t+1, diagonal(V, C).
% A new object: nothing to compare with (weight 1).
observation(pos(A)):t+1 ~ val(_) :=
    object(A), \+ pos(A):t ~= _.

prior_var(A, P):t+1 := object(A), seen(A):t, motion_var(P).
prior_var(A, P):t+1 := object(A), \+ seen(A):t, \+ lost_anywhere(A):t, reappear_var(P).
% An object lost while the camera saw nothing, and not under anything since, may have been moved
% anywhere on the table (two look-alike containers swapped): where it shows up again says little
% about which particle was right, so that the hypotheses of which one is which (the identity
% hypotheses the runner keeps in the particles) survive until something decides them.
prior_var(A, P):t+1 := object(A), \+ seen(A):t, lost_anywhere(A):t, lost_var(P).
predictive_var(A, V):t+1 := prior_var(A, P):t+1, obs_var(R), V is P + R.

diagonal(V, [V, 0, 0, 0, V, 0, 0, 0, V]).

% The choices of pick_occluder/1 when occluders Os come down onto the object: `behind` with
% behind_when_covered, each of Os with an equal share of the rest.
behind_or_under(Os, [W:behind | Ws]) :-
    behind_when_covered(W), length(Os, K), WO is (1 - W) / K,
    findall(WO:O, member(O, Os), Ws).
