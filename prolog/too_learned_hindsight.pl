/*  too_learned_hindsight.pl -- the theory of occlusion with rules learned from experience.

    Written by `anchoring learn-theory`: the hand-written occlusion rules of
    too.pl are replaced by a tree learned (ddc learn) from data_hindsight.pl:
    30802 groundings of occluder(A, O):t+1, 69 clauses,
    training log-likelihood -11596.6; search seed 0.
    Command: anchoring learn-theory out/learn/data_hindsight.pl --seed 0 --out prolog/too_learned_hindsight.pl --plots docs/images
    Everything else is too.pl's (motion, observations, blind frames, the
    transitive clause). Regenerate it rather than edit it; edit
    too.pl for the rest.
*/

/*  too.pl -- the theory of occlusion: which object may hide which, and where a hidden object is.

    An ordinary DDC program, filtered over time by the particle filter (prolog/ddc.pl);
    edit it freely.  What the runner tells it at every step t+1 (one camera frame):

      facts         object(A)          every anchor that exists, as an atom (ball-1 -> ball_1)
                    category(A, C)     its best category: ball, mug, cup, box, can, skin, ...
                    observed(A)        A was perceived in this frame
      observations  observation(pos(A)) ~= (X,Y,Z)   its perceived position (metres, z up)

    What it reads back, per particle: pos(A):t ~= (X,Y,Z) and occluded_by(A, O):t.
*/

% ------------------------------------------------------------------ parameters
% Variances are per axis, in square metres; one step is one camera frame.
obs_var(0.0001).            % measurement noise of a perceived position: (1 cm)^2
motion_var(0.0004).         % how far a perceived object moves in one frame: (2 cm)^2
reappear_var(0.0025).       % where a hidden object shows up again, around its belief: (5 cm)^2
follow_var(0.000004).       % jitter of a hidden object that follows its occluder: (2 mm)^2
wander_var(0.0001).         % how far a hidden object under nothing may move in a frame: (1 cm)^2
coast_keep(0.9).            % fraction of its velocity a hidden object under nothing keeps per frame
follow_keep(0.95).          % fraction of its offset from the occluder's centre kept per frame
occluder_reach(0.15).       % an occluder is within 15 cm of the object in the table plane ...
occluder_rise(0.02).        % ... and its centre is no more than 2 cm lower than the object's
cover_height(0.12).         % a container whose centre rises more than this above the object's
                            % centre no longer covers it (it was lifted)

% ------------------------------------------------------------------ background knowledge
% What carries what it hides through space (a hand lifts a grasped object); containers slide
% over the table and what they cover stays on the table.
carrier(skin) := true.
carrier(hand) := true.


% ------------------------------------------------------------------ seen and hidden
seen(A):t+1 := observed(A).
hidden(A):t+1 := object(A), \+ observed(A).
% The camera saw nothing at all (covered by a hand): an object lost now could be anywhere.
blind:t+1 := \+ observed(_).


% An object hidden while blind stays "lost anywhere" until an occluder explains it.
lost_anywhere(A):t+1 := hidden(A):t+1, blind:t+1, \+ occluded_by(A, _):t+1.
lost_anywhere(A):t+1 := lost_anywhere(A):t, hidden(A):t+1, \+ occluded_by(A, _):t+1.

% ------------------------------------------------------------------ occlusion
% ------------------------------------------------------------------ learned occlusion rules
% How the learned occluder/2 (below) is used, as the paper's theory uses its occluder rule
% (section 2.3): the pairs it is about are a hidden A and a perceived O (the data's examples);
% O is a candidate occluder of the hidden A when the particle
% draws occluder(A, O):t+1 ~= true; the particle picks one candidate uniformly, or `behind`
% when A has just vanished (it stays where it was, hidden from view: as in too.pl); the
% occlusion goes on while O is perceived and the particle draws occluder(A, O):t+1 ~= true.
pair(A, O):t+1 := hidden(A):t+1, observed(O), O \== A.
occluder_candidate(A, O):t+1 :=
    pair(A, O):t+1, \+ occluded_by(A, O):t, occluder(A, O):t+1 ~= true.
pick_occluder(A):t+1 ~ uniform(Os) :=
    hidden(A):t+1, seen(A):t, \+ occluded_by(A, _):t,
    findall_forward(O, occluder_candidate(A, O):t+1, Os0), sort(Os0, Os1), Os1 \== [],
    Os = [behind | Os1].
pick_occluder(A):t+1 ~ uniform(Os) :=
    hidden(A):t+1, \+ seen(A):t, \+ occluded_by(A, _):t,
    findall_forward(O, occluder_candidate(A, O):t+1, Os0), sort(Os0, Os), Os \== [].
occluded_by(A, O):t+1 := hidden(A):t+1, pick_occluder(A):t+1 ~= O, O \== behind.
occluded_by(A, O):t+1 :=
    occluded_by(A, O):t, pair(A, O):t+1, occluder(A, O):t+1 ~= true.

% The learned rules (ddc learn): a distributional logic tree for occluder/2 (each path from its
% root to a leaf is one clause of the tree), with the background knowledge it reads.
distance(A, O):t+1 ~ val(D) :=
    pos(A):t ~= (X, Y, _),
    pos(O):t+1 ~= (XO, YO, _),
    D is sqrt((X-XO)**2+(Y-YO)**2).
rise(A, O):t+1 ~ val(H) :=
    pos(A):t ~= (_, _, Z),
    pos(O):t+1 ~= (_, _, ZO),
    H is ZO-Z.
kind(A):t+1 ~ val(C) :=
    category(A, C).

% occluder(Occluded, Occluder):t+1: 69 clauses, 30802 groundings, training log-likelihood -11596.6 (mean -0.14569 per grounding), 112 parameters.
occluder(Occluded, Occluder):t+1 ~ finite([P1:true, P2:false]) :=
    pair(Occluded, Occluder):t+1,
    (   distance(Occluded, Occluder):t+1 ~= Distance
    ->  (   occluded_by(Occluded, Occluder):t
        ->  % n = 2772 (weight 8835.63), log-likelihood -43.0818, logistic
            logistic([Distance], [-73.0883, 7.75027], P1),
            P2 is 1-P1
        ;   (   kind(Occluder):t+1 ~= ball
            ->  % n = 2148 (weight 6636.37), log-likelihood -88.151, logistic
                logistic([Distance], [-45.165, 0.790038], P1),
                P2 is 1-P1
            ;   kind(Occluder):t+1 ~= box
            ->  (   kind(Occluded):t+1 ~= ball
                ->  (   rise(Occluded, Occluder):t+1 ~= Rise
                    ->  (   Rise < 0.0
                        ->  % n = 8 (weight 28), log-likelihood -0.949243, finite
                            P1 = 0.0333333,
                            P2 = 0.9666667
                        ;   Rise < 0.1
                        ->  % n = 4882 (weight 13462), log-likelihood -1696.33, logistic
                            logistic([Distance], [-24.8374, 1.84494], P1),
                            P2 is 1-P1
                        ;   % n = 449 (weight 605), log-likelihood -15.3005, logistic
                            logistic([Distance], [-64.2382, 6.57997], P1),
                            P2 is 1-P1
                        )
                    ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                        logistic([Distance], [-25.5551, 1.92628], P1),
                        P2 is 1-P1
                    )
                ;   kind(Occluded):t+1 ~= box
                ->  % n = 366 (weight 676.192), log-likelihood -332.09, logistic
                    logistic([Distance], [-8.35196, -0.166164], P1),
                    P2 is 1-P1
                ;   kind(Occluded):t+1 ~= can
                ->  % n = 692 (weight 1304), log-likelihood -6.67704, logistic
                    logistic([Distance], [-65.2735, 7.74784], P1),
                    P2 is 1-P1
                ;   kind(Occluded):t+1 ~= cup
                ->  (   rise(Occluded, Occluder):t+1 ~= Rise4
                    ->  (   Rise4 < 0.0
                        ->  % n = 48 (weight 112), log-likelihood -26.237, finite
                            P1 = 0.0701754,
                            P2 = 0.9298246
                        ;   Rise4 < 0.1
                        ->  % n = 281 (weight 621), log-likelihood -238.705, logistic
                            logistic([Distance], [-6.8548, -0.605699], P1),
                            P2 is 1-P1
                        ;   (   seen(Occluded):t
                            ->  % n = 10, log-likelihood -6.73585, finite
                                P1 = 0.583333,
                                P2 = 0.416667
                            ;   % n = 50 (weight 74), log-likelihood -11.213, logistic
                                logistic([Distance], [-142.137, 8.16861], P1),
                                P2 is 1-P1
                            )
                        )
                    ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                        logistic([Distance], [-9.04483, -0.276256], P1),
                        P2 is 1-P1
                    )
                ;   kind(Occluded):t+1 ~= mug
                ->  (   rise(Occluded, Occluder):t+1 ~= Rise8
                    ->  (   Rise8 < 0.0
                        ->  % n = 83 (weight 251), log-likelihood -59.5489, finite
                            P1 = 0.0671937,
                            P2 = 0.9328063
                        ;   Rise8 < 0.1
                        ->  % n = 919 (weight 1799), log-likelihood -695.133, logistic
                            logistic([Distance], [-14.0218, 1.36846], P1),
                            P2 is 1-P1
                        ;   % n = 71 (weight 91), log-likelihood -4.81054, logistic
                            logistic([Distance], [-26.2954, 2.18246], P1),
                            P2 is 1-P1
                        )
                    ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                        logistic([Distance], [-12.0529, 0.771649], P1),
                        P2 is 1-P1
                    )
                ;   kind(Occluded):t+1 ~= skin
                ->  % n = 207 (weight 599), log-likelihood -0.997502, finite
                    P1 = 0.00166389,
                    P2 = 0.99833611
                ;   \+ kind(Occluded):t+1 ~= _
                ->  % n = 0, too few groundings for a model of its own: the parent's model, logistic
                    logistic([Distance], [-21.4607, 1.54204], P1),
                    P2 is 1-P1
                )
            ;   kind(Occluder):t+1 ~= can
            ->  % n = 1606 (weight 6182), log-likelihood -8.93759, logistic
                logistic([Distance], [-60.05, 1.88126], P1),
                P2 is 1-P1
            ;   kind(Occluder):t+1 ~= cup
            ->  (   rise(Occluded, Occluder):t+1 ~= Rise12
                ->  (   Rise12 < 0.0
                    ->  (   kind(Occluded):t+1 ~= ball
                        ->  % n = 176 (weight 544), log-likelihood -28.9474, logistic
                            logistic([Distance], [-67.4281, -1.36588], P1),
                            P2 is 1-P1
                        ;   kind(Occluded):t+1 ~= box
                        ->  % n = 209 (weight 709), log-likelihood -12.251, logistic
                            logistic([Distance], [-25.8762, 0.485414], P1),
                            P2 is 1-P1
                        ;   kind(Occluded):t+1 ~= can
                        ->  % n = 169 (weight 673), log-likelihood -12.8174, logistic
                            logistic([Distance], [-83.9149, 8.70475], P1),
                            P2 is 1-P1
                        ;   kind(Occluded):t+1 ~= cup
                        ->  % n = 46 (weight 102), log-likelihood -0.985515, finite
                            P1 = 0.00961538,
                            P2 = 0.99038462
                        ;   kind(Occluded):t+1 ~= mug
                        ->  (   lost_anywhere(Occluded):t
                            ->  % n = 61 (weight 189), log-likelihood -0.992128, finite
                                P1 = 0.0052356,
                                P2 = 0.9947644
                            ;   % n = 497 (weight 1533), log-likelihood -95.248, logistic
                                logistic([Distance], [-21.2843, -1.31229], P1),
                                P2 is 1-P1
                            )
                        ;   kind(Occluded):t+1 ~= skin
                        ->  (   lost_anywhere(Occluded):t
                            ->  % n = 69 (weight 229), log-likelihood -0.993494, finite
                                P1 = 0.004329,
                                P2 = 0.995671
                            ;   % n = 200 (weight 612), log-likelihood -124.158, logistic
                                logistic([Distance], [-13.0371, 0.530511], P1),
                                P2 is 1-P1
                            )
                        ;   \+ kind(Occluded):t+1 ~= _
                        ->  % n = 0, too few groundings for a model of its own: the parent's model, logistic
                            logistic([Distance], [-12.5587, -1.65288], P1),
                            P2 is 1-P1
                        )
                    ;   Rise12 < 0.1
                    ->  (   kind(Occluded):t+1 ~= ball
                        ->  % n = 4740 (weight 11192), log-likelihood -3848.92, logistic
                            logistic([Distance], [-12.1522, 0.98927], P1),
                            P2 is 1-P1
                        ;   kind(Occluded):t+1 ~= box
                        ->  % n = 27 (weight 63), log-likelihood -0.976764, finite
                            P1 = 0.0153846,
                            P2 = 0.9846154
                        ;   kind(Occluded):t+1 ~= can
                        ->  % n = 75 (weight 255), log-likelihood -6.38297, logistic
                            logistic([Distance], [-57.0276, 3.33301], P1),
                            P2 is 1-P1
                        ;   kind(Occluded):t+1 ~= cup
                        ->  % n = 68 (weight 176), log-likelihood -0.991552, finite
                            P1 = 0.00561798,
                            P2 = 0.99438202
                        ;   kind(Occluded):t+1 ~= mug
                        ->  % n = 167 (weight 463), log-likelihood -27.3053, logistic
                            logistic([Distance], [-21.8186, 0.597226], P1),
                            P2 is 1-P1
                        ;   kind(Occluded):t+1 ~= skin
                        ->  % n = 11 (weight 27), log-likelihood -0.947466, finite
                            P1 = 0.0344828,
                            P2 = 0.9655172
                        ;   \+ kind(Occluded):t+1 ~= _
                        ->  % n = 0, too few groundings for a model of its own: the parent's model, logistic
                            logistic([Distance], [-12.4081, 0.917559], P1),
                            P2 is 1-P1
                        )
                    ;   % n = 239 (weight 271), log-likelihood -48.9648, logistic
                        logistic([Distance], [-19.4581, 1.95707], P1),
                        P2 is 1-P1
                    )
                ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                    logistic([Distance], [-12.1177, 0.437228], P1),
                    P2 is 1-P1
                )
            ;   kind(Occluder):t+1 ~= mug
            ->  (   kind(Occluded):t+1 ~= ball
                ->  (   rise(Occluded, Occluder):t+1 ~= Rise16
                    ->  (   Rise16 < 0.0
                        ->  % n = 45 (weight 97), log-likelihood -0.98478, finite
                            P1 = 0.010101,
                            P2 = 0.989899
                        ;   Rise16 < 0.1
                        ->  (   lost_anywhere(Occluded):t
                            ->  (   seen(Occluder):t
                                ->  % n = 136 (weight 612), log-likelihood -0.997555, finite
                                    P1 = 0.00162866,
                                    P2 = 0.99837134
                                ;   % n = 14 (weight 22), log-likelihood -8.30717, logistic
                                    logistic([Distance], [-13.8142, 1.68842], P1),
                                    P2 is 1-P1
                                )
                            ;   % n = 4837 (weight 11557), log-likelihood -3000.5, logistic
                                logistic([Distance], [-18.9219, 1.65062], P1),
                                P2 is 1-P1
                            )
                        ;   % n = 263 (weight 311), log-likelihood -61.5888, logistic
                            logistic([Distance], [-21.4356, 1.1602], P1),
                            P2 is 1-P1
                        )
                    ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                        logistic([Distance], [-19.3071, 1.59613], P1),
                        P2 is 1-P1
                    )
                ;   kind(Occluded):t+1 ~= box
                ->  % n = 357 (weight 921.396), log-likelihood -64.6509, logistic
                    logistic([Distance], [-47.5652, 5.04365], P1),
                    P2 is 1-P1
                ;   kind(Occluded):t+1 ~= can
                ->  % n = 448 (weight 1336), log-likelihood -4.45849, logistic
                    logistic([Distance], [-91.0212, 7.4146], P1),
                    P2 is 1-P1
                ;   kind(Occluded):t+1 ~= cup
                ->  % n = 332 (weight 805.752), log-likelihood -40.7991, logistic
                    logistic([Distance], [-43.6432, 1.87652], P1),
                    P2 is 1-P1
                ;   kind(Occluded):t+1 ~= mug
                ->  (   rise(Occluded, Occluder):t+1 ~= Rise20
                    ->  (   Rise20 < 0.0
                        ->  (   lost_anywhere(Occluded):t
                            ->  % n = 9 (weight 45), log-likelihood -0.967779, finite
                                P1 = 0.0212766,
                                P2 = 0.9787234
                            ;   % n = 265 (weight 478.635), log-likelihood -293.871, logistic
                                logistic([Distance], [-2.65976, -0.124827], P1),
                                P2 is 1-P1
                            )
                        ;   Rise20 < 0.1
                        ->  % n = 248 (weight 756), log-likelihood -38.0428, logistic
                            logistic([Distance], [-24.9147, 0.198828], P1),
                            P2 is 1-P1
                        ;   % n = 114 (weight 146), log-likelihood -0.989834, finite
                            P1 = 0.00675676,
                            P2 = 0.99324324
                        )
                    ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                        logistic([Distance], [-5.85591, -0.546934], P1),
                        P2 is 1-P1
                    )
                ;   kind(Occluded):t+1 ~= skin
                ->  (   rise(Occluded, Occluder):t+1 ~= Rise24
                    ->  (   Rise24 < 0.0
                        ->  % n = 347 (weight 1407), log-likelihood -8.55465, finite
                            P1 = 0.00141945,
                            P2 = 0.99858055
                        ;   Rise24 < 0.1
                        ->  % n = 10 (weight 14), log-likelihood -5.83963, finite
                            P1 = 0.1875,
                            P2 = 0.8125
                        ;   % n = 0, too few groundings for a model of its own: the parent's model, finite
                            P1 = 0.00281096,
                            P2 = 0.99718904
                        )
                    ;   % n = 0, too few groundings for a model of its own: the parent's model, finite
                        P1 = 0.00281096,
                        P2 = 0.99718904
                    )
                ;   \+ kind(Occluded):t+1 ~= _
                ->  % n = 0, too few groundings for a model of its own: the parent's model, logistic
                    logistic([Distance], [-19.6387, 1.44953], P1),
                    P2 is 1-P1
                )
            ;   kind(Occluder):t+1 ~= skin
            ->  (   kind(Occluded):t+1 ~= ball
                ->  (   rise(Occluded, Occluder):t+1 ~= Rise28
                    ->  (   Rise28 < 0.0
                        ->  % n = 40 (weight 56), log-likelihood -0.973938, finite
                            P1 = 0.0172414,
                            P2 = 0.9827586
                        ;   Rise28 < 0.1
                        ->  % n = 394 (weight 466), log-likelihood -156.701, finite
                            P1 = 0.106838,
                            P2 = 0.893162
                        ;   % n = 669 (weight 973), log-likelihood -263.851, logistic
                            logistic([Distance], [-11.6438, 0.0474778], P1),
                            P2 is 1-P1
                        )
                    ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                        logistic([Distance], [-7.51998, -0.655742], P1),
                        P2 is 1-P1
                    )
                ;   kind(Occluded):t+1 ~= box
                ->  % n = 84 (weight 87.8297), log-likelihood -8.90769, finite
                    P1 = 0.0309952,
                    P2 = 0.9690048
                ;   kind(Occluded):t+1 ~= can
                ->  % n = 58 (weight 90), log-likelihood -5.78476, finite
                    P1 = 0.0217391,
                    P2 = 0.9782609
                ;   kind(Occluded):t+1 ~= cup
                ->  % n = 256 (weight 311.829), log-likelihood -27.7958, logistic
                    logistic([Distance], [-46.2958, 2.14204], P1),
                    P2 is 1-P1
                ;   kind(Occluded):t+1 ~= mug
                ->  % n = 372 (weight 476.365), log-likelihood -144.021, logistic
                    logistic([Distance], [-13.6397, 0.00919763], P1),
                    P2 is 1-P1
                ;   kind(Occluded):t+1 ~= skin
                ->  % n = 208 (weight 304), log-likelihood -12.2253, finite
                    P1 = 0.00980392,
                    P2 = 0.99019608
                ;   \+ kind(Occluded):t+1 ~= _
                ->  % n = 0, too few groundings for a model of its own: the parent's model, logistic
                    logistic([Distance], [-8.69386, -0.860849], P1),
                    P2 is 1-P1
                )
            ;   \+ kind(Occluder):t+1 ~= _
            ->  % n = 0, too few groundings for a model of its own: the parent's model, logistic
                logistic([Distance], [-18.3593, 1.03951], P1),
                P2 is 1-P1
            )
        )
    ;   % n = 0, too few groundings for a model of its own: the parent's model, finite
        P1 = 0.220216,
        P2 = 0.779784
    ).
% Transitive occlusion (section 5.3 of the paper; remove this clause to switch it off): an
% object whose occluder is itself hidden stays with it, under whatever hides the occluder (or,
% while the occluder is under nothing, where the occluder is believed to be: a box lowered
% over a mug hides the mug a few frames before it covers it).
occluded_by(A, O):t+1 :=
    occluded_by(A, O):t, hidden(A):t+1, hidden(O):t+1.

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
% such as a hand also lifts it).  Its offset from the occluder's centre is kept with
% follow_keep and jittered with follow_var, so the belief settles within the occluder's
% footprint (spread sqrt(follow_var / (1 - follow_keep^2)), 6 mm) instead of wandering
% further off frame after frame; its height hardly jitters (an object under a container stays
% on the table).
pos(A):t+1 ~ gaussian([MX, MY, MZ], [V, 0, 0, 0, V, 0, 0, 0, VZ]) :=
    hidden(A):t+1, occluded_by(A, O):t, occluded_by(A, O):t+1,
    pos(O):t ~= (X0, Y0, Z0), pos(O):t+1 ~= (X1, Y1, Z1), pos(A):t ~= (X, Y, Z),
    follow_keep(K), MX is X1 + K*(X - X0), MY is Y1 + K*(Y - Y0),
    (   category(O, CO), carrier(CO) -> MZ is Z + Z1 - Z0 ; MZ = Z ),
    follow_var(V), VZ is V / 100.
% Hidden under an occluder that has just been picked: under it, at the object's own height.
pos(A):t+1 ~ gaussian([XO, YO, Z], C) :=
    hidden(A):t+1, occluded_by(A, O):t+1, \+ occluded_by(A, O):t,
    pos(O):t+1 ~= (XO, YO, _), pos(A):t ~= (_, _, Z),
    follow_var(V), diagonal(V, C).
% Hidden under nothing (behind something, or left on the table): it may be moved while unseen
% (a mug carried behind a box, a container swapped while merged with another in the image).
% It coasts on with the velocity it had when it vanished, slowing down (coast_keep per frame,
% so at most 1 / (1 - coast_keep) frames' worth of its last motion: a static object stays),
% and its belief spreads by wander_var per frame in the table plane; a reappearance then
% weights the particles by where they had it, and matching finds the particles near it.
pos(A):t+1 ~ gaussian([MX, MY, Z], [V, 0, 0, 0, V, 0, 0, 0, VZ]) :=
    hidden(A):t+1, \+ occluded_by(A, _):t+1, pos(A):t ~= (X, Y, Z),
    velocity(A, VX, VY):t+1, MX is X + VX, MY is Y + VY,
    wander_var(V), VZ is V / 100.

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
prior_var(A, P):t+1 := object(A), \+ seen(A):t, reappear_var(P).
predictive_var(A, V):t+1 := prior_var(A, P):t+1, obs_var(R), V is P + R.

diagonal(V, [V, 0, 0, 0, V, 0, 0, 0, V]).
