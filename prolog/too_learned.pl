/*  too_learned.pl -- the theory of occlusion with rules learned from experience.

    Written by `anchoring learn-theory`: the hand-written occlusion rules of
    too.pl are replaced by a tree learned (ddc learn) from data_truth.pl:
    78093 groundings of occluder(A, O):t+1, 85 clauses,
    training log-likelihood -24831.9; search seed 0.
    Command: anchoring learn-theory out/learn/data_truth.pl --seed 0 --out prolog/too_learned.pl --plots docs/images
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
lost_var(0.04).             % where an object lost while the camera saw nothing shows up again:
                            % (20 cm)^2 around its belief (it may have been moved anywhere)
follow_var(0.000004).       % jitter of a hidden object that follows its occluder: (2 mm)^2
wander_var(0.0001).         % how far a hidden object under nothing may move in a frame: (1 cm)^2
coast_keep(0.9).            % fraction of its velocity a hidden object under nothing keeps per frame
follow_keep(0.95).          % fraction of its offset from the occluder's centre kept per frame
occluder_reach(0.15).       % an occluder is within 15 cm of the object in the table plane ...
occluder_rise(0.02).        % ... and its centre is no more than 2 cm lower than the object's
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


% An object hidden while blind stays "lost anywhere" until an occluder explains it.
lost_anywhere(A):t+1 := hidden(A):t+1, blind:t+1, \+ occluded_by(A, _):t+1.
lost_anywhere(A):t+1 := lost_anywhere(A):t, hidden(A):t+1, \+ occluded_by(A, _):t+1.

% ------------------------------------------------------------------ occlusion
% ------------------------------------------------------------------ learned occlusion rules
% How the learned occluder/2 (below) is used, as the paper's theory uses its occluder rule
% (section 2.3): the pairs it is about are a hidden A and a perceived O (the data's examples)
% that the affordances above allow (a ball hides nothing, a hand is never hidden: the paper's
% experiments keep that knowledge too; the tree gives a ball as occluder a probability of
% about 1e-4 per frame, and one particle of a hidden ball under the other, identical ball is
% enough for the matching, which takes the best particle, to swap them);
% O is a candidate occluder of the hidden A when the particle
% draws occluder(A, O):t+1 ~= true; the particle picks one candidate uniformly, or `behind`
% when A has just vanished (it stays where it was, hidden from view: as in too.pl); the
% occlusion goes on while O is perceived and the particle draws occluder(A, O):t+1 ~= true.
pair(A, O):t+1 :=
    hidden(A):t+1, observed(O), O \== A, can_be_occluded(A), can_occlude(O).
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
lift(O):t+1 ~ val(H) :=
    pos(O):t ~= (_, _, Z0),
    pos(O):t+1 ~= (_, _, Z1),
    H is Z1-Z0.
kind(A):t+1 ~ val(C) :=
    category(A, C).

% occluder(Occluded, Occluder):t+1: 85 clauses, 78093 groundings, training log-likelihood -24831.9 (mean -0.108256 per grounding), 125 parameters.
occluder(Occluded, Occluder):t+1 ~ finite([P1:true, P2:false]) :=
    pair(Occluded, Occluder):t+1,
    (   occluded_by(Occluded, Occluder):t
    ->  (   lift(Occluder):t+1 ~= Lift
        ->  (   rise(Occluded, Occluder):t+1 ~= Rise
            ->  (   Rise < 0.0
                ->  % n = 124 (weight 484), log-likelihood -0.996911, finite
                    P1 = 0.99794239,
                    P2 = 0.00205761
                ;   Rise < 0.1
                ->  (   kind(Occluded):t+1 ~= ball
                    ->  (   kind(Occluder):t+1 ~= ball
                        ->  % n = 0, too few groundings for a model of its own: the parent's model, logistic
                            logistic([Lift], [-113.799, 5.34454], P1),
                            P2 is 1-P1
                        ;   kind(Occluder):t+1 ~= box
                        ->  (   distance(Occluded, Occluder):t+1 ~= Distance
                            ->  % n = 643 (weight 2223), log-likelihood -65.0611, logistic
                                logistic([Lift, Distance], [-570.391, 905.637, 5.61594], P1),
                                P2 is 1-P1
                            ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                                logistic([Lift], [-422.136, 5.46676], P1),
                                P2 is 1-P1
                            )
                        ;   kind(Occluder):t+1 ~= can
                        ->  % n = 0, too few groundings for a model of its own: the parent's model, logistic
                            logistic([Lift], [-113.799, 5.34454], P1),
                            P2 is 1-P1
                        ;   kind(Occluder):t+1 ~= cup
                        ->  % n = 1089 (weight 3573), log-likelihood -76.9197, logistic
                            logistic([Lift], [-144.834, 5.76303], P1),
                            P2 is 1-P1
                        ;   kind(Occluder):t+1 ~= mug
                        ->  (   distance(Occluded, Occluder):t+1 ~= Distance2
                            ->  % n = 939 (weight 3311), log-likelihood -63.9198, logistic
                                logistic([Lift, Distance2], [-604.091, 1180.09, 5.29976], P1),
                                P2 is 1-P1
                            ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                                logistic([Lift], [-308.477, 5.60647], P1),
                                P2 is 1-P1
                            )
                        ;   kind(Occluder):t+1 ~= skin
                        ->  % n = 138 (weight 166), log-likelihood -22.5162, finite
                            P1 = 0.9642857,
                            P2 = 0.0357143
                        ;   \+ kind(Occluder):t+1 ~= _
                        ->  % n = 0, too few groundings for a model of its own: the parent's model, logistic
                            logistic([Lift], [-113.799, 5.34454], P1),
                            P2 is 1-P1
                        )
                    ;   kind(Occluded):t+1 ~= box
                    ->  % n = 0, too few groundings for a model of its own: the parent's model, logistic
                        logistic([Lift], [-147.7, 5.21651], P1),
                        P2 is 1-P1
                    ;   kind(Occluded):t+1 ~= can
                    ->  % n = 577 (weight 1349), log-likelihood -39.6806, logistic
                        logistic([Lift], [-452.058, 6.64955], P1),
                        P2 is 1-P1
                    ;   kind(Occluded):t+1 ~= cup
                    ->  % n = 5, too few groundings for a model of its own: the parent's model, log-likelihood -0.00298734, logistic
                        logistic([Lift], [-147.7, 5.21651], P1),
                        P2 is 1-P1
                    ;   kind(Occluded):t+1 ~= mug
                    ->  % n = 83 (weight 367), log-likelihood -7.20678, finite
                        P1 = 0.99457995,
                        P2 = 0.00542005
                    ;   kind(Occluded):t+1 ~= skin
                    ->  % n = 0, too few groundings for a model of its own: the parent's model, logistic
                        logistic([Lift], [-147.7, 5.21651], P1),
                        P2 is 1-P1
                    ;   \+ kind(Occluded):t+1 ~= _
                    ->  % n = 0, too few groundings for a model of its own: the parent's model, logistic
                        logistic([Lift], [-147.7, 5.21651], P1),
                        P2 is 1-P1
                    )
                ;   % n = 802 (weight 1306), log-likelihood -101.2, logistic
                    logistic([Lift], [-54.1251, 4.45189], P1),
                    P2 is 1-P1
                )
            ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                logistic([Lift], [-85.2481, 5.05158], P1),
                P2 is 1-P1
            )
        ;   % n = 0, too few groundings for a model of its own: the parent's model, finite
            P1 = 0.99092758,
            P2 = 0.00907242
        )
    ;   (   distance(Occluded, Occluder):t+1 ~= Distance4
        ->  (   kind(Occluded):t+1 ~= ball
            ->  (   kind(Occluder):t+1 ~= ball
                ->  % n = 2798 (weight 9922), log-likelihood -0.999849, finite
                    P1 = 0.000100766,
                    P2 = 0.999899234
                ;   kind(Occluder):t+1 ~= box
                ->  (   rise(Occluded, Occluder):t+1 ~= Rise4
                    ->  (   Rise4 < 0.0
                        ->  % n = 241 (weight 1073), log-likelihood -0.998604, finite
                            P1 = 0.000930233,
                            P2 = 0.999069767
                        ;   Rise4 < 0.1
                        ->  (   lost_anywhere(Occluded):t
                            ->  % n = 118 (weight 550), log-likelihood -2.13875, logistic
                                logistic([Distance4], [-50.5145, 2.34709], P1),
                                P2 is 1-P1
                            ;   (   seen(Occluded):t
                                ->  % n = 119, log-likelihood -0.987558, finite
                                    P1 = 0.00826446,
                                    P2 = 0.99173554
                                ;   % n = 7094 (weight 20578), log-likelihood -4372.83, logistic
                                    logistic([Distance4], [-13.9051, 0.411773], P1),
                                    P2 is 1-P1
                                )
                            )
                        ;   % n = 609 (weight 845), log-likelihood -91.6787, logistic
                            logistic([Distance4], [-22.8211, -0.23725], P1),
                            P2 is 1-P1
                        )
                    ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                        logistic([Distance4], [-14.4202, 0.360344], P1),
                        P2 is 1-P1
                    )
                ;   kind(Occluder):t+1 ~= can
                ->  % n = 1822 (weight 7542), log-likelihood -0.999801, finite
                    P1 = 0.000132556,
                    P2 = 0.999867444
                ;   kind(Occluder):t+1 ~= cup
                ->  (   rise(Occluded, Occluder):t+1 ~= Rise8
                    ->  (   Rise8 < 0.0
                        ->  (   lost_anywhere(Occluded):t
                            ->  % n = 76 (weight 232), log-likelihood -6.74502, finite
                                P1 = 0.00854701,
                                P2 = 0.99145299
                            ;   % n = 581 (weight 1617), log-likelihood -513.024, finite
                                P1 = 0.0969734,
                                P2 = 0.9030266
                            )
                        ;   Rise8 < 0.1
                        ->  (   lost_anywhere(Occluded):t
                            ->  (   seen(Occluder):t
                                ->  % n = 118 (weight 466), log-likelihood -0.996792, finite
                                    P1 = 0.00213675,
                                    P2 = 0.99786325
                                ;   % n = 11 (weight 15), log-likelihood -9.56045, finite
                                    P1 = 0.352941,
                                    P2 = 0.647059
                                )
                            ;   (   seen(Occluded):t
                                ->  % n = 98, log-likelihood -5.69509, logistic
                                    logistic([Distance4], [-31.823, 2.07911], P1),
                                    P2 is 1-P1
                                ;   % n = 7268 (weight 18836), log-likelihood -7894.06, logistic
                                    logistic([Distance4], [-5.24457, -0.423311], P1),
                                    P2 is 1-P1
                                )
                            )
                        ;   % n = 476 (weight 552), log-likelihood -90.3871, logistic
                            logistic([Distance4], [-13.8413, -0.0771486], P1),
                            P2 is 1-P1
                        )
                    ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                        logistic([Distance4], [-5.11868, -0.568126], P1),
                        P2 is 1-P1
                    )
                ;   kind(Occluder):t+1 ~= mug
                ->  (   rise(Occluded, Occluder):t+1 ~= Rise12
                    ->  (   Rise12 < 0.0
                        ->  % n = 491 (weight 1771), log-likelihood -15.7594, finite
                            P1 = 0.00169205,
                            P2 = 0.99830795
                        ;   Rise12 < 0.1
                        ->  (   lost_anywhere(Occluded):t
                            ->  % n = 124 (weight 364), log-likelihood -9.96381, logistic
                                logistic([Distance4], [-48.4227, 1.05198], P1),
                                P2 is 1-P1
                            ;   % n = 7436 (weight 18060), log-likelihood -7247.9, logistic
                                logistic([Distance4], [-7.83112, 0.180452], P1),
                                P2 is 1-P1
                            )
                        ;   % n = 339 (weight 399), log-likelihood -42.5162, logistic
                            logistic([Distance4], [-15.2828, -0.419905], P1),
                            P2 is 1-P1
                        )
                    ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                        logistic([Distance4], [-8.04772, 0.08178], P1),
                        P2 is 1-P1
                    )
                ;   kind(Occluder):t+1 ~= skin
                ->  (   rise(Occluded, Occluder):t+1 ~= Rise16
                    ->  (   Rise16 < 0.0
                        ->  % n = 65 (weight 97), log-likelihood -9.91632, finite
                            P1 = 0.030303,
                            P2 = 0.969697
                        ;   Rise16 < 0.1
                        ->  % n = 649 (weight 745), log-likelihood -402.546, finite
                            P1 = 0.231593,
                            P2 = 0.768407
                        ;   (   lost_anywhere(Occluded):t
                            ->  % n = 18 (weight 26), log-likelihood -0.945559, finite
                                P1 = 0.0357143,
                                P2 = 0.9642857
                            ;   % n = 1136 (weight 1504), log-likelihood -840.076, logistic
                                logistic([Distance4], [-1.6019, -0.684152], P1),
                                P2 is 1-P1
                            )
                        )
                    ;   % n = 0, too few groundings for a model of its own: the parent's model, finite
                        P1 = 0.232519,
                        P2 = 0.767481
                    )
                ;   \+ kind(Occluder):t+1 ~= _
                ->  % n = 0, too few groundings for a model of its own: the parent's model, logistic
                    logistic([Distance4], [-8.67328, -0.224571], P1),
                    P2 is 1-P1
                )
            ;   kind(Occluded):t+1 ~= box
            ->  % n = 5630 (weight 16954), log-likelihood -0.999912, finite
                P1 = 5.89762e-5,
                P2 = 0.9999410238
            ;   kind(Occluded):t+1 ~= can
            ->  (   kind(Occluder):t+1 ~= ball
                ->  (   seen(Occluder):t
                    ->  % n = 1146 (weight 4794), log-likelihood -25.2652, finite
                        P1 = 0.000834028,
                        P2 = 0.999165972
                    ;   (   lift(Occluder):t+1 ~= Lift2
                        ->  % n = 70 (weight 90), log-likelihood -15.9822, logistic
                            logistic([Distance4, Lift2], [1.59874, 38.41, -3.55372], P1),
                            P2 is 1-P1
                        ;   % n = 0, too few groundings for a model of its own: the parent's model, finite
                            P1 = 0.108696,
                            P2 = 0.891304
                        )
                    )
                ;   kind(Occluder):t+1 ~= box
                ->  (   rise(Occluded, Occluder):t+1 ~= Rise20
                    ->  (   Rise20 < 0.0
                        ->  % n = 484 (weight 1004), log-likelihood -25.733, logistic
                            logistic([Distance4], [-58.206, 4.28248], P1),
                            P2 is 1-P1
                        ;   Rise20 < 0.1
                        ->  (   lost_anywhere(Occluded):t
                            ->  % n = 62 (weight 154), log-likelihood -12.0061, logistic
                                logistic([Distance4], [-19.4899, 0.501112], P1),
                                P2 is 1-P1
                            ;   % n = 2120 (weight 4892), log-likelihood -2013.91, logistic
                                logistic([Distance4], [-9.29869, 0.828388], P1),
                                P2 is 1-P1
                            )
                        ;   % n = 446 (weight 630), log-likelihood -51.3961, finite
                            P1 = 0.0174051,
                            P2 = 0.9825949
                        )
                    ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                        logistic([Distance4], [-11.4498, 1.03451], P1),
                        P2 is 1-P1
                    )
                ;   kind(Occluder):t+1 ~= can
                ->  % n = 645 (weight 2905), log-likelihood -0.999484, finite
                    P1 = 0.000343997,
                    P2 = 0.999656003
                ;   kind(Occluder):t+1 ~= cup
                ->  % n = 2261 (weight 8277), log-likelihood -0.999819, finite
                    P1 = 0.000120788,
                    P2 = 0.999879212
                ;   kind(Occluder):t+1 ~= mug
                ->  % n = 2253 (weight 7513), log-likelihood -0.9998, finite
                    P1 = 0.000133067,
                    P2 = 0.999866933
                ;   kind(Occluder):t+1 ~= skin
                ->  (   rise(Occluded, Occluder):t+1 ~= Rise24
                    ->  (   Rise24 < 0.0
                        ->  % n = 26 (weight 30), log-likelihood -0.952461, finite
                            P1 = 0.03125,
                            P2 = 0.96875
                        ;   Rise24 < 0.1
                        ->  (   lift(Occluder):t+1 ~= Lift4
                            ->  % n = 415 (weight 419), log-likelihood -208.809, logistic
                                logistic([Distance4, Lift4], [-3.12978, -41.0483, 2.05129], P1),
                                P2 is 1-P1
                            ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                                logistic([Distance4], [-3.32992, 2.1457], P1),
                                P2 is 1-P1
                            )
                        ;   (   seen(Occluder):t
                            ->  (   lost_anywhere(Occluded):t
                                ->  % n = 14 (weight 18), log-likelihood -4.09371, finite
                                    P1 = 0.1,
                                    P2 = 0.9
                                ;   (   lift(Occluder):t+1 ~= Lift6
                                    ->  % n = 988 (weight 1012), log-likelihood -426.772, logistic
                                        logistic([Distance4, Lift6], [-5.72537, -23.5366, 3.20192], P1),
                                        P2 is 1-P1
                                    ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                                        logistic([Distance4], [-5.28312, 2.98427], P1),
                                        P2 is 1-P1
                                    )
                                )
                            ;   % n = 19, log-likelihood -0.927013, finite
                                P1 = 0.047619,
                                P2 = 0.952381
                            )
                        )
                    ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                        logistic([Distance4], [-4.65336, 2.52629], P1),
                        P2 is 1-P1
                    )
                ;   \+ kind(Occluder):t+1 ~= _
                ->  % n = 0, too few groundings for a model of its own: the parent's model, logistic
                    logistic([Distance4], [-8.57333, -0.445478], P1),
                    P2 is 1-P1
                )
            ;   kind(Occluded):t+1 ~= cup
            ->  (   kind(Occluder):t+1 ~= ball
                ->  % n = 848 (weight 3144), log-likelihood -0.999523, finite
                    P1 = 0.000317864,
                    P2 = 0.999682136
                ;   kind(Occluder):t+1 ~= box
                ->  % n = 1468 (weight 4880), log-likelihood -0.999693, finite
                    P1 = 0.000204834,
                    P2 = 0.999795166
                ;   kind(Occluder):t+1 ~= can
                ->  % n = 602 (weight 2474), log-likelihood -0.999394, finite
                    P1 = 0.000403877,
                    P2 = 0.999596123
                ;   kind(Occluder):t+1 ~= cup
                ->  % n = 1237 (weight 4005), log-likelihood -0.999626, finite
                    P1 = 0.000249563,
                    P2 = 0.999750437
                ;   kind(Occluder):t+1 ~= mug
                ->  % n = 1529 (weight 5225), log-likelihood -0.999713, finite
                    P1 = 0.000191314,
                    P2 = 0.999808686
                ;   kind(Occluder):t+1 ~= skin
                ->  % n = 476 (weight 592), log-likelihood -61.8509, logistic
                    logistic([Distance4], [-8.95436, -2.01379], P1),
                    P2 is 1-P1
                ;   \+ kind(Occluder):t+1 ~= _
                ->  % n = 0, too few groundings for a model of its own: the parent's model, logistic
                    logistic([Distance4], [-10.2078, -5.37812], P1),
                    P2 is 1-P1
                )
            ;   kind(Occluded):t+1 ~= mug
            ->  (   kind(Occluder):t+1 ~= ball
                ->  % n = 913 (weight 2937), log-likelihood -0.99949, finite
                    P1 = 0.000340252,
                    P2 = 0.999659748
                ;   kind(Occluder):t+1 ~= box
                ->  (   lost_anywhere(Occluded):t
                    ->  % n = 200 (weight 776), log-likelihood -0.998071, finite
                        P1 = 0.00128535,
                        P2 = 0.99871465
                    ;   % n = 1301 (weight 3489), log-likelihood -30.0244, logistic
                        logistic([Distance4], [-193.604, 4.62729], P1),
                        P2 is 1-P1
                    )
                ;   kind(Occluder):t+1 ~= can
                ->  % n = 460 (weight 1968), log-likelihood -0.999238, finite
                    P1 = 0.000507614,
                    P2 = 0.999492386
                ;   kind(Occluder):t+1 ~= cup
                ->  % n = 1611 (weight 5563), log-likelihood -0.99973, finite
                    P1 = 0.000179695,
                    P2 = 0.999820305
                ;   kind(Occluder):t+1 ~= mug
                ->  % n = 1497 (weight 4133), log-likelihood -0.999637, finite
                    P1 = 0.000241838,
                    P2 = 0.999758162
                ;   kind(Occluder):t+1 ~= skin
                ->  % n = 501 (weight 641), log-likelihood -0.997666, finite
                    P1 = 0.00155521,
                    P2 = 0.99844479
                ;   \+ kind(Occluder):t+1 ~= _
                ->  % n = 0, too few groundings for a model of its own: the parent's model, logistic
                    logistic([Distance4], [-90.8124, -0.586072], P1),
                    P2 is 1-P1
                )
            ;   kind(Occluded):t+1 ~= skin
            ->  % n = 12784 (weight 42648), log-likelihood -0.999965, finite
                P1 = 2.34467e-5,
                P2 = 0.9999765533
            ;   \+ kind(Occluded):t+1 ~= _
            ->  % n = 0, too few groundings for a model of its own: the parent's model, logistic
                logistic([Distance4], [-8.90334, -0.885625], P1),
                P2 is 1-P1
            )
        ;   % n = 0, too few groundings for a model of its own: the parent's model, finite
            P1 = 0.0582182,
            P2 = 0.9417818
        )
    ).
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
