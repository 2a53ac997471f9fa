/*  too_base.pl -- the vocabulary and the frame of every theory of occlusion.

    Hand-written, and included (`:- include(too_base).`) by the hand-written theory (too.pl)
    and by the theories `anchoring learn-theory` writes: what the runner tells a theory at
    every step t+1 (one camera frame), what it reads back, and how a perceived object's
    position is filtered and weighs the particles.

      facts         object(A)          every anchor that exists, as an atom (ball-1 -> ball_1)
                    category(A, C)     its best category: ball, mug, cup, box, can, skin, ...
                    observed(A)        A was perceived in this frame
      observations  observation(pos(A)) ~= (X,Y,Z)   its perceived position (metres, z up);
                                                      a hand's (a carrier's) is where it
                                                      closes: its percept's grip point

    What the runner reads back, per particle: pos(A):t ~= (X,Y,Z) and occluded_by(A, O):t.

    What the including theory defines: occluded_by(A, O):t+1 (what hides a hidden object);
    pos(A):t+1 of a hidden object (and vel(A):t+1 if it coasts); prior_var(A, P):t+1, the
    variance (per axis, square metres) of where A is now around where it was believed in the
    previous frame, which the perceived object's filtering and the observation model below
    read; the parameters it reads: obs_var/1, the measurement noise of a perceived position
    (per axis, square metres; too_parameters.pl, or learned).
*/

% ------------------------------------------------------------------ facts
% What the runner asserts at every step (above): declared, so that reading them is not taken
% for a call to a predicate defined nowhere.
:- dynamic((object/1, category/2, observed/1)).
% The heights of the kinds (a learned theory's, fitted from the perceived heights; too.pl has
% none): the carriers' rules measure a grip's height over an object from its top.
:- dynamic(kind_height/2).
% How far a hidden object's height spreads a frame (a learned theory's, fitted; too.pl has none:
% too_motion.pl's height_spread/2).
:- dynamic(height_var/1).

% ------------------------------------------------------------------ seen and hidden
seen(A):t+1 := observed(A).
hidden(A):t+1 := object(A), \+ observed(A).
% The camera saw nothing at all (covered by a hand): an object lost now could be anywhere.
blind:t+1 := \+ observed(_).

% An object hidden while blind stays "lost anywhere" until an occluder explains it.
lost_anywhere(A):t+1 := hidden(A):t+1, blind:t+1, \+ occluded_by(A, _):t+1.
lost_anywhere(A):t+1 := lost_anywhere(A):t, hidden(A):t+1, \+ occluded_by(A, _):t+1.

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

% The velocity (metres per frame, in the table plane) of a perceived object: the change of its
% filtered position (the theory says what a hidden object's is).
vel(A):t+1 ~ val((VX, VY)) :=
    observed(A), seen(A):t, pos(A):t ~= (X0, Y0, _), pos(A):t+1 ~= (X1, Y1, _),
    VX is X1 - X0, VY is Y1 - Y0.

% ------------------------------------------------------------------ observation model
% A perceived position weights each particle by its predictive density: motion + noise for an
% object that was perceived in the previous frame, a wider one for an object that reappears.
observation(pos(A)):t+1 ~ gaussian([X, Y, Z], C) :=
    pos(A):t ~= (X, Y, Z), predictive_var(A, V):t+1, diagonal(V, C).
% A new object: nothing to compare with (weight 1).
observation(pos(A)):t+1 ~ val(_) :=
    object(A), \+ pos(A):t ~= _.

predictive_var(A, V):t+1 := prior_var(A, P):t+1, obs_var(R), V is P + R.

diagonal(V, [V, 0, 0, 0, V, 0, 0, 0, V]).
