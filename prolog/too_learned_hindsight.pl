/*  too_learned_hindsight.pl -- the theory of occlusion with rules learned from experience.

    Written by `anchoring learn-theory`: a tree learned (ddc learn) from
    data_hindsight.pl: 14101 groundings of occluder(A, O):t+1,
    90 clauses, training log-likelihood -3007.47;
    and one for released(A):t+1 from 1030 frames a hand held an object
    (3 clauses, training log-likelihood -35.4546);
    search seed 0.
    Command: anchoring learn-theory out/learn/data_hindsight.pl --seed 0 --out prolog/too_learned_hindsight.pl --plots docs/images
    The hand-written parts are included from prolog/too/ (too_base.pl, too_learned_glue.pl, too_motion.pl):
    regenerate this file rather than edit it; edit those for the rest.  The
    parameters are fitted from the motion samples beside the data.
*/

:- include('too/too_base.pl').

% ------------------------------------------------------------------ learned parameters
% Fitted from the motion samples beside the data (python/probanchor/learning/
% motion_parameters.py: maximum-likelihood variances, least-squares AR(1) kept
% fractions, quantiles for reaches and heights, Laplace's rule for a probability);
% variances per axis in square metres, one step is one camera frame.
obs_var(3.67e-06).  % the measurement noise of a perceived position (m², per axis); 91,121 samples
motion_var(3.155e-05).  % how far a perceived object moves in a frame (m², per axis); 122,017 samples
reappear_var(0.001607).  % where a hidden object is seen again, around its belief (m²); 1,292 samples
lost_var(0.07162).  % the same for an object lost while the camera saw nothing (m²); 8,160 samples
follow_keep(0.999).  % the fraction of its offset from its occluder a hidden object keeps; 25 samples
follow_var(2.044e-07).  % the jitter of that offset per frame (m²); 25 samples
coast_keep(0.9003).  % the fraction of its velocity a hidden object under nothing keeps; 41 samples
wander_var(0.0003978).  % how far such an object may move besides (m²); 41 samples
rest_var(1.325e-06).  % how far one that stood still as it vanished may move (m²); 86 samples
height_var(1e-08).  % how far a hidden object's height may move (m² a frame); 133 samples
grip_reach(0.06474).  % how far (table plane) a hand's grip may be from what it takes (m); 22 samples
grip_height(0.1356).  % how far above its top (m); 22 samples
occluder_rise(0.005354).  % how far below its centre (m); 22 samples
grip_drop(0.04095).  % how far what a hand holds is below its grip (m); 22 samples
grip_rise(0.00109).  % how far a hand's grip rises in a frame when it lifts (m); 289 samples
moving_speed(0.004).  % (m a frame) what the fits above call moving as it vanished (wander_var) and still (rest_var)
% The height of each kind (m): the median of its perceived heights; a grip's height
% over an object is measured from its top (too/too_motion.pl).
kind_height(ball, 0.059).  % 1,210 samples
kind_height(bottle, 0.2128).  % 727 samples
kind_height(bowl, 0.0869).  % 702 samples
kind_height(box, 0.134).  % 1,750 samples
kind_height(can, 0.1232).  % 548 samples
kind_height(cup, 0.1037).  % 1,564 samples
kind_height(mug, 0.1026).  % 1,659 samples

% ------------------------------------------------------------------ learned affordances
% Read from the data (python/probanchor/learning/occlusion_affordances.py): the share
% of the hidden objects a kind hides, of the pairs in which it is hidden itself,
% and of the occlusions going on in which it still holds what it hid when lifted
% off (Laplace's rule; the data points' weight in the comment).  A kind is asked
% about as an occluder when it hides at least 0.01 of them and is no
% carrier, as hidden when it is at least 0.01 of the time; a carrier holds
% what it hid when lifted off with a probability above 1/2, read from a weight of
% at least 50 data points (too/too_motion.pl's carriers' rules apply to
% it).
hides(ball, 0.0006716).  % 11,432
hides(bottle, 0.0001507).  % 6,633
hides(bowl, 0.04529).  % 6,644
hides(box, 0.1937).  % 20,638
hides(can, 0.0001981).  % 5,045
hides(cup, 0.08791).  % 16,469
hides(mug, 0.1322).  % 17,163
hides(skin, 0.336).  % 3,715
hidden_share(ball, 0.1889).  % 33,319
hidden_share(bottle, 0.1053).  % 1,816
hidden_share(bowl, 0.0146).  % 6,848
hidden_share(box, 0.01233).  % 9,245
hidden_share(can, 0.1189).  % 4,280
hidden_share(cup, 0.1274).  % 12,882
hidden_share(mug, 0.02769).  % 15,167
hidden_share(skin, 0.000239).  % 4,182
carries(box, 0.8).  % 3
carries(skin, 0.9973).  % 560
carrier(skin).
can_occlude(O) := category(O, C), hides(C, P), P >= 0.01, \+ is_carrier(O).
is_carrier(O) := category(O, C), carrier(C).
hand_known := object(O), is_carrier(O).
can_be_occluded(A) := category(A, C), hidden_share(C, P), P >= 0.01.

:- include('too/too_learned_glue.pl').
% The onset reach (m): 90% of the 37 onsets in the data (1 far out left out) were within 0.05926 m; times 2.0.
onset_reach(0.1185).
% The reach of the kinds with onsets enough for one of their own.
onset_reach(box, 0.1075).  % 14 onsets, (1 far out left out) 90% within 0.05376 m

% The learned rules (ddc learn): a distributional logic tree for occluder/2 (each path from its
% root to a leaf is one clause of the tree), with the background knowledge it reads.
learned_from(own, ['data_hindsight.pl'],
    [occluder(_, _):t+1],
    [ type(occluder(obj, obj):t+1),
      type(pair(obj, obj):t+1),
      type(occluded_by(obj, obj):t),
      type(seen(obj):t),
      type(lost_anywhere(obj):t),
      type(distance(obj, obj):t+1),
      type(distance3(obj, obj):t+1),
      type(rise(obj, obj):t+1),
      type(lift(obj):t+1),
      type(moved(obj):t+1),
      type(kind(obj):t+1),
      rv(occluder(_, _):t+1, boolean),
      rv(distance(_, _):t+1, continuous),
      rv(distance3(_, _):t+1, continuous),
      rv(rise(_, _):t+1, continuous),
      rv(lift(_):t+1, continuous),
      rv(moved(_):t+1, continuous),
      rv(kind(_):t+1, discrete([ball, bottle, bowl, box, can, cup, mug, skin])),
      examples(occluder(A, B):t+1, pair(A, B):t+1)]).

% Background knowledge from the data that the learned clauses call.
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
moved(O):t+1 ~ val(M) :=
    pos(O):t ~= (X0, Y0, Z0),
    pos(O):t+1 ~= (X1, Y1, Z1),
    M is sqrt((X1-X0)**2+(Y1-Y0)**2+(Z1-Z0)**2).
kind(A):t+1 ~ val(C) :=
    category(A, C).

% occluder(Occluded, Occluder):t+1: 90 clauses, 14101 groundings, training log-likelihood -3007.47 (mean -0.106727 per grounding), 121 parameters.
occluder(Occluded, Occluder):t+1 ~ finite([P1:true, P2:false]) :=
    pair(Occluded, Occluder):t+1,
    (   distance(Occluded, Occluder):t+1 ~= Distance
    ->  (   kind(Occluder):t+1 ~= ball
        ->  (   moved(Occluder):t+1 ~= Moved
            ->  (   Moved < 0.004
                ->  % n = 172 (weight 812), log-likelihood -0.998156, finite
                    P1 = 0.0012285,
                    P2 = 0.9987715
                ;   % n = 321 (weight 342), log-likelihood -22.9313, logistic
                    logistic([Distance], [-24.7121, -1.05499], P1),
                    P2 is 1-P1
                )
            ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                logistic([Distance], [-28.6356, -1.9345], P1),
                P2 is 1-P1
            )
        ;   kind(Occluder):t+1 ~= bottle
        ->  % n = 158 (weight 550), log-likelihood -0.99728, finite
            P1 = 0.00181159,
            P2 = 0.99818841
        ;   kind(Occluder):t+1 ~= bowl
        ->  (   occluded_by(Occluded, Occluder):t
            ->  % n = 123 (weight 291), log-likelihood -0.994873, finite
                P1 = 0.99658703,
                P2 = 0.00341297
            ;   (   kind(Occluded):t+1 ~= ball
                ->  (   lost_anywhere(Occluded):t
                    ->  % n = 49 (weight 117), log-likelihood -0.987348, finite
                        P1 = 0.00840336,
                        P2 = 0.99159664
                    ;   (   moved(Occluder):t+1 ~= Moved3
                        ->  (   Moved3 < 0.004
                            ->  (   seen(Occluder):t
                                ->  (   lift(Occluder):t+1 ~= Lift
                                    ->  % n = 210 (weight 534), log-likelihood -208.57, logistic
                                        logistic([Distance, Lift], [44.712, -1363.58, -2.50434], P1),
                                        P2 is 1-P1
                                    ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                                        logistic([Distance], [45.339, -2.51388], P1),
                                        P2 is 1-P1
                                    )
                                ;   % n = 3 (weight 15), log-likelihood -0.909369, finite
                                    P1 = 0.0588235,
                                    P2 = 0.9411765
                                )
                            ;   % n = 187 (weight 239), log-likelihood -112.638, finite
                                P1 = 0.182573,
                                P2 = 0.817427
                            )
                        ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                            logistic([Distance], [15.2315, -1.94425], P1),
                            P2 is 1-P1
                        )
                    )
                ;   kind(Occluded):t+1 ~= bottle
                ->  % n = 27 (weight 47), log-likelihood -0.969106, finite
                    P1 = 0.0204082,
                    P2 = 0.9795918
                ;   kind(Occluded):t+1 ~= bowl
                ->  % n = 319 (weight 771), log-likelihood -7.95195, finite
                    P1 = 0.00258732,
                    P2 = 0.99741268
                ;   kind(Occluded):t+1 ~= box
                ->  % n = 23 (weight 35), log-likelihood -17.5418, finite
                    P1 = 0.216216,
                    P2 = 0.783784
                ;   kind(Occluded):t+1 ~= can
                ->  % n = 9, too few groundings for a model of its own: the parent's model, log-likelihood -0.837814, finite
                    P1 = 0.0888889,
                    P2 = 0.9111111
                ;   kind(Occluded):t+1 ~= cup
                ->  % n = 64 (weight 164), log-likelihood -0.99094, finite
                    P1 = 0.0060241,
                    P2 = 0.9939759
                ;   kind(Occluded):t+1 ~= mug
                ->  % n = 40 (weight 84), log-likelihood -0.982467, finite
                    P1 = 0.0116279,
                    P2 = 0.9883721
                ;   kind(Occluded):t+1 ~= skin
                ->  % n = 4 (weight 8), too few groundings for a model of its own: the parent's model, log-likelihood -0.744723, finite
                    P1 = 0.0888889,
                    P2 = 0.9111111
                ;   \+ kind(Occluded):t+1 ~= _
                ->  % n = 0, too few groundings for a model of its own: the parent's model, finite
                    P1 = 0.0888889,
                    P2 = 0.9111111
                )
            )
        ;   kind(Occluder):t+1 ~= box
        ->  (   kind(Occluded):t+1 ~= ball
            ->  (   occluded_by(Occluded, Occluder):t
                ->  % n = 611 (weight 2023), log-likelihood -0.999259, finite
                    P1 = 0.999506173,
                    P2 = 0.000493827
                ;   (   lost_anywhere(Occluded):t
                    ->  % n = 229 (weight 889), log-likelihood -8.0947, finite
                        P1 = 0.00224467,
                        P2 = 0.99775533
                    ;   (   rise(Occluded, Occluder):t+1 ~= Rise
                        ->  (   Rise < 0.0
                            ->  % n = 0, too few groundings for a model of its own: the parent's model, logistic
                                logistic([Distance], [-22.0468, 1.58829], P1),
                                P2 is 1-P1
                            ;   Rise < 0.1
                            ->  (   moved(Occluder):t+1 ~= Moved6
                                ->  (   Moved6 < 0.004
                                    ->  (   lift(Occluder):t+1 ~= Lift2
                                        ->  % n = 1235 (weight 1507), log-likelihood -773.412, logistic
                                            logistic([Distance, Lift2], [-14.4217, 523.538, 1.664], P1),
                                            P2 is 1-P1
                                        ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                                            logistic([Distance], [-14.5051, 1.60442], P1),
                                            P2 is 1-P1
                                        )
                                    ;   (   lift(Occluder):t+1 ~= Lift4
                                        ->  % n = 341 (weight 369), log-likelihood -235.76, logistic
                                            logistic([Distance, Lift4], [-20.0267, 37.6181, 1.08982], P1),
                                            P2 is 1-P1
                                        ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                                            logistic([Distance], [-17.6758, 0.931007], P1),
                                            P2 is 1-P1
                                        )
                                    )
                                ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                                    logistic([Distance], [-18.2588, 1.53565], P1),
                                    P2 is 1-P1
                                )
                            ;   % n = 72 (weight 76), log-likelihood -16.2071, logistic
                                logistic([Distance], [-102.192, 3.20086], P1),
                                P2 is 1-P1
                            )
                        ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                            logistic([Distance], [-22.0468, 1.58829], P1),
                            P2 is 1-P1
                        )
                    )
                )
            ;   kind(Occluded):t+1 ~= bottle
            ->  % n = 21 (weight 29), log-likelihood -0.950905, finite
                P1 = 0.0322581,
                P2 = 0.9677419
            ;   kind(Occluded):t+1 ~= bowl
            ->  % n = 36 (weight 88), log-likelihood -0.98325, finite
                P1 = 0.0111111,
                P2 = 0.9888889
            ;   kind(Occluded):t+1 ~= box
            ->  % n = 181 (weight 593), log-likelihood -7.68868, finite
                P1 = 0.00336134,
                P2 = 0.99663866
            ;   kind(Occluded):t+1 ~= can
            ->  (   occluded_by(Occluded, Occluder):t
                ->  % n = 128 (weight 440), log-likelihood -0.996603, finite
                    P1 = 0.99773756,
                    P2 = 0.00226244
                ;   (   lift(Occluder):t+1 ~= Lift6
                    ->  % n = 563 (weight 675), log-likelihood -88.6056, logistic
                        logistic([Distance, Lift6], [-244.115, 78.0129, 7.10235], P1),
                        P2 is 1-P1
                    ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                        logistic([Distance], [-221.203, 6.40433], P1),
                        P2 is 1-P1
                    )
                )
            ;   kind(Occluded):t+1 ~= cup
            ->  (   occluded_by(Occluded, Occluder):t
                ->  % n = 299 (weight 1455), log-likelihood -0.99897, finite
                    P1 = 0.999313658,
                    P2 = 0.000686342
                ;   (   moved(Occluder):t+1 ~= Moved9
                    ->  (   Moved9 < 0.004
                        ->  (   lost_anywhere(Occluded):t
                            ->  % n = 1 (weight 5), too few groundings for a model of its own: the parent's model, log-likelihood -91.1247, logistic
                                logistic([Distance], [120.221, -3.49719], P1),
                                P2 is 1-P1
                            ;   % n = 539 (weight 731), log-likelihood -206.121, logistic
                                logistic([Distance], [183.812, -5.6388], P1),
                                P2 is 1-P1
                            )
                        ;   % n = 62, log-likelihood -30.4801, finite
                            P1 = 0.203125,
                            P2 = 0.796875
                        )
                    ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                        logistic([Distance], [63.2982, -1.77685], P1),
                        P2 is 1-P1
                    )
                )
            ;   kind(Occluded):t+1 ~= mug
            ->  (   rise(Occluded, Occluder):t+1 ~= Rise4
                ->  (   Rise4 < 0.0
                    ->  % n = 75 (weight 363), log-likelihood -0.995885, finite
                        P1 = 0.00273973,
                        P2 = 0.99726027
                    ;   Rise4 < 0.1
                    ->  % n = 289 (weight 581), log-likelihood -123.837, logistic
                        logistic([Distance], [-171.011, 5.49786], P1),
                        P2 is 1-P1
                    ;   % n = 22 (weight 26), log-likelihood -4.49176, finite
                        P1 = 0.0714286,
                        P2 = 0.9285714
                    )
                ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                    logistic([Distance], [-181.559, 5.48368], P1),
                    P2 is 1-P1
                )
            ;   kind(Occluded):t+1 ~= skin
            ->  % n = 70 (weight 162), log-likelihood -0.990829, finite
                P1 = 0.00609756,
                P2 = 0.99390244
            ;   \+ kind(Occluded):t+1 ~= _
            ->  % n = 0, too few groundings for a model of its own: the parent's model, logistic
                logistic([Distance], [-56.9159, 2.66216], P1),
                P2 is 1-P1
            )
        ;   kind(Occluder):t+1 ~= can
        ->  % n = 157 (weight 509), log-likelihood -0.997062, finite
            P1 = 0.00195695,
            P2 = 0.99804305
        ;   kind(Occluder):t+1 ~= cup
        ->  (   kind(Occluded):t+1 ~= ball
            ->  (   lost_anywhere(Occluded):t
                ->  (   seen(Occluder):t
                    ->  % n = 137 (weight 437), log-likelihood -0.99658, finite
                        P1 = 0.0022779,
                        P2 = 0.9977221
                    ;   % n = 12 (weight 44), log-likelihood -11.0569, finite
                        P1 = 0.0869565,
                        P2 = 0.9130435
                    )
                ;   (   moved(Occluder):t+1 ~= Moved12
                    ->  (   Moved12 < 0.004
                        ->  % n = 1383 (weight 2383), log-likelihood -39.1408, logistic
                            logistic([Distance], [-170.321, 6.81141], P1),
                            P2 is 1-P1
                        ;   (   occluded_by(Occluded, Occluder):t
                            ->  % n = 167 (weight 207), log-likelihood -0.992808, finite
                                P1 = 0.99521531,
                                P2 = 0.00478469
                            ;   % n = 182, log-likelihood -66.6812, logistic
                                logistic([Distance], [-49.2158, 2.61058], P1),
                                P2 is 1-P1
                            )
                        )
                    ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                        logistic([Distance], [-90.1816, 5.42928], P1),
                        P2 is 1-P1
                    )
                )
            ;   kind(Occluded):t+1 ~= bottle
            ->  % n = 3, too few groundings for a model of its own: the parent's model, log-likelihood -3.27965e-06, logistic
                logistic([Distance], [-191.115, 2.3102], P1),
                P2 is 1-P1
            ;   kind(Occluded):t+1 ~= bowl
            ->  % n = 24 (weight 40), log-likelihood -0.963902, finite
                P1 = 0.0238095,
                P2 = 0.9761905
            ;   kind(Occluded):t+1 ~= box
            ->  % n = 57 (weight 237), log-likelihood -0.993712, finite
                P1 = 0.0041841,
                P2 = 0.9958159
            ;   kind(Occluded):t+1 ~= can
            ->  % n = 17 (weight 25), log-likelihood -0.943508, finite
                P1 = 0.037037,
                P2 = 0.962963
            ;   kind(Occluded):t+1 ~= cup
            ->  % n = 446 (weight 1202), log-likelihood -0.998754, finite
                P1 = 0.000830565,
                P2 = 0.999169435
            ;   kind(Occluded):t+1 ~= mug
            ->  % n = 115 (weight 439), log-likelihood -0.996595, finite
                P1 = 0.00226757,
                P2 = 0.99773243
            ;   kind(Occluded):t+1 ~= skin
            ->  % n = 0, too few groundings for a model of its own: the parent's model, logistic
                logistic([Distance], [-191.115, 2.3102], P1),
                P2 is 1-P1
            ;   \+ kind(Occluded):t+1 ~= _
            ->  % n = 0, too few groundings for a model of its own: the parent's model, logistic
                logistic([Distance], [-191.115, 2.3102], P1),
                P2 is 1-P1
            )
        ;   kind(Occluder):t+1 ~= mug
        ->  (   kind(Occluded):t+1 ~= ball
            ->  (   occluded_by(Occluded, Occluder):t
                ->  % n = 560 (weight 2260), log-likelihood -0.999337, finite
                    P1 = 0.999557913,
                    P2 = 0.000442087
                ;   (   moved(Occluder):t+1 ~= Moved15
                    ->  (   Moved15 < 0.004
                        ->  % n = 1306 (weight 1734), log-likelihood -149.268, logistic
                            logistic([Distance], [-74.4167, 4.79158], P1),
                            P2 is 1-P1
                        ;   % n = 193 (weight 217), log-likelihood -117.44, logistic
                            logistic([Distance], [-22.9963, 1.05415], P1),
                            P2 is 1-P1
                        )
                    ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                        logistic([Distance], [-61.829, 3.79515], P1),
                        P2 is 1-P1
                    )
                )
            ;   kind(Occluded):t+1 ~= bottle
            ->  % n = 0, too few groundings for a model of its own: the parent's model, logistic
                logistic([Distance], [-151.205, 3.84635], P1),
                P2 is 1-P1
            ;   kind(Occluded):t+1 ~= bowl
            ->  % n = 11 (weight 15), log-likelihood -0.909369, finite
                P1 = 0.0588235,
                P2 = 0.9411765
            ;   kind(Occluded):t+1 ~= box
            ->  % n = 93 (weight 305), log-likelihood -0.995107, finite
                P1 = 0.00325733,
                P2 = 0.99674267
            ;   kind(Occluded):t+1 ~= can
            ->  % n = 4 (weight 8), too few groundings for a model of its own: the parent's model, log-likelihood -3.06243e-05, logistic
                logistic([Distance], [-151.205, 3.84635], P1),
                P2 is 1-P1
            ;   kind(Occluded):t+1 ~= cup
            ->  % n = 22 (weight 34), log-likelihood -0.95781, finite
                P1 = 0.0277778,
                P2 = 0.9722222
            ;   kind(Occluded):t+1 ~= mug
            ->  % n = 296 (weight 1100), log-likelihood -0.998638, finite
                P1 = 0.000907441,
                P2 = 0.999092559
            ;   kind(Occluded):t+1 ~= skin
            ->  % n = 34 (weight 158), log-likelihood -0.990599, finite
                P1 = 0.00625,
                P2 = 0.99375
            ;   \+ kind(Occluded):t+1 ~= _
            ->  % n = 0, too few groundings for a model of its own: the parent's model, logistic
                logistic([Distance], [-151.205, 3.84635], P1),
                P2 is 1-P1
            )
        ;   kind(Occluder):t+1 ~= skin
        ->  (   kind(Occluded):t+1 ~= ball
            ->  (   occluded_by(Occluded, Occluder):t
                ->  % n = 186 (weight 246), log-likelihood -0.993941, finite
                    P1 = 0.99596774,
                    P2 = 0.00403226
                ;   % n = 274 (weight 290), log-likelihood -79.1983, logistic
                    logistic([Distance], [-50.8296, 3.22132], P1),
                    P2 is 1-P1
                )
            ;   kind(Occluded):t+1 ~= bottle
            ->  % n = 625 (weight 442), log-likelihood -301.489, finite
                P1 = 0.573841,
                P2 = 0.426159
            ;   kind(Occluded):t+1 ~= bowl
            ->  % n = 200 (weight 248), log-likelihood -68.3356, logistic
                logistic([Distance], [-74.9547, 4.99438], P1),
                P2 is 1-P1
            ;   kind(Occluded):t+1 ~= box
            ->  (   occluded_by(Occluded, Occluder):t
                ->  % n = 78 (weight 102), log-likelihood -0.985515, finite
                    P1 = 0.99038462,
                    P2 = 0.00961538
                ;   % n = 108 (weight 124), log-likelihood -69.2455, logistic
                    logistic([Distance], [-44.2382, 2.25314], P1),
                    P2 is 1-P1
                )
            ;   kind(Occluded):t+1 ~= can
            ->  % n = 92 (weight 104), log-likelihood -11.3771, logistic
                logistic([Distance], [-69.2643, 5.28313], P1),
                P2 is 1-P1
            ;   kind(Occluded):t+1 ~= cup
            ->  (   occluded_by(Occluded, Occluder):t
                ->  % n = 137 (weight 181), log-likelihood -0.991783, finite
                    P1 = 0.99453552,
                    P2 = 0.00546448
                ;   (   rise(Occluded, Occluder):t+1 ~= Rise8
                    ->  (   Rise8 < 0.0
                        ->  % n = 0, too few groundings for a model of its own: the parent's model, finite
                            P1 = 0.774011,
                            P2 = 0.225989
                        ;   Rise8 < 0.1
                        ->  % n = 34 (weight 38), log-likelihood -6.09678, logistic
                            logistic([Distance], [1818.46, -18.468], P1),
                            P2 is 1-P1
                        ;   % n = 129 (weight 137), log-likelihood -68.0051, finite
                            P1 = 0.798561,
                            P2 = 0.201439
                        )
                    ;   % n = 0, too few groundings for a model of its own: the parent's model, finite
                        P1 = 0.774011,
                        P2 = 0.225989
                    )
                )
            ;   kind(Occluded):t+1 ~= mug
            ->  % n = 536 (weight 636), log-likelihood -31.6481, logistic
                logistic([Distance], [-63.334, 6.41893], P1),
                P2 is 1-P1
            ;   kind(Occluded):t+1 ~= skin
            ->  % n = 0, too few groundings for a model of its own: the parent's model, logistic
                logistic([Distance], [-23.1332, 2.17881], P1),
                P2 is 1-P1
            ;   \+ kind(Occluded):t+1 ~= _
            ->  % n = 0, too few groundings for a model of its own: the parent's model, logistic
                logistic([Distance], [-23.1332, 2.17881], P1),
                P2 is 1-P1
            )
        ;   \+ kind(Occluder):t+1 ~= _
        ->  % n = 0, too few groundings for a model of its own: the parent's model, logistic
            logistic([Distance], [-50.7547, 1.84532], P1),
            P2 is 1-P1
        )
    ;   % n = 0, too few groundings for a model of its own: the parent's model, finite
        P1 = 0.539103,
        P2 = 0.460897
    ).

% When a hand lets go of what it carries (ddc learn, from the carries beside the data): a
% distributional logic tree for released/1, with the background knowledge it reads.
learned_from(own, ['data_hindsight.release.pl'],
    [released(_):t+1],
    [ type(released(obj):t+1),
      type(carried(obj):t+1),
      type(height(obj):t+1),
      type(highest(obj):t+1),
      rv(released(_):t+1, boolean),
      rv(height(_):t+1, continuous),
      rv(highest(_):t+1, continuous),
      examples(released(A):t+1, carried(A):t+1)]).

% Background knowledge from the data that the learned clauses call.
height(A):t+1 ~ val(H) :=
    pos(A):t ~= (_, _, Z),
    rest_z(A):t ~= R,
    H is Z-R.
highest(A):t+1 ~ val(H) :=
    top(A):t ~= H.

% released(Held):t+1: 3 clauses, 1030 groundings, training log-likelihood -35.4546 (mean -0.0344219 per grounding), 6 parameters.
released(Held):t+1 ~ finite([P1:true, P2:false]) :=
    carried(Held):t+1,
    (   height(Held):t+1 ~= Height
    ->  (   highest(Held):t+1 ~= Highest
        ->  % n = 1030, log-likelihood -35.4546, logistic
            logistic([Height, Highest], [-92.3002, 31.7449, -4.97658], P1),
            P2 is 1-P1
        ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
            logistic([Height], [-54.3579, -2.08271], P1),
            P2 is 1-P1
        )
    ;   % n = 0, too few groundings for a model of its own: the parent's model, finite
        P1 = 0.0222868,
        P2 = 0.9777132
    ).

:- include('too/too_motion.pl').
