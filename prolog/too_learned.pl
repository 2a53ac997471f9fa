/*  too_learned.pl -- the theory of occlusion with rules learned from experience.

    Written by `anchoring learn-theory`: a tree learned (ddc learn) from
    data_truth.pl: 28836 groundings of occluder(A, O):t+1,
    92 clauses, training log-likelihood -7558.29;
    and one for released(A):t+1 from 2528 frames a hand held an object
    (3 clauses, training log-likelihood -78.9072);
    search seed 0.
    Command: anchoring learn-theory out/learn/data_truth.pl --seed 0 --out prolog/too_learned.pl --plots docs/images
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
obs_var(5.212e-06).  % the measurement noise of a perceived position (m², per axis); 105,130 samples
motion_var(2.935e-05).  % how far a perceived object moves in a frame (m², per axis); 121,605 samples
reappear_var(0.00201).  % where a hidden object is seen again, around its belief (m²); 1,358 samples
lost_var(0.07289).  % the same for an object lost while the camera saw nothing (m²); 8,202 samples
follow_keep(0.8715).  % the fraction of its offset from its occluder a hidden object keeps; 13,933 samples
follow_var(1.687e-05).  % the jitter of that offset per frame (m²); 13,933 samples
coast_keep(0.8858).  % the fraction of its velocity a hidden object under nothing keeps; 219 samples
wander_var(0.0001852).  % how far such an object may move besides (m²); 219 samples
grip_reach(0.06716).  % how far (table plane) a hand's grip may be from what it takes (m); 49 samples
grip_height(0.1155).  % how far above its top (m); 49 samples
occluder_rise(0.006988).  % how far below its centre (m); 49 samples
grip_drop(0.02061).  % how far what a hand holds is below its grip (m); 2,521 samples
grip_rise(0.001076).  % how far a hand's grip rises in a frame when it lifts (m); 728 samples
% The height of each kind (m): the median of its perceived heights; a grip's height
% over an object is measured from its top (too/too_motion.pl).
kind_height(ball, 0.0593).  % 1,167 samples
kind_height(bottle, 0.2127).  % 701 samples
kind_height(bowl, 0.0869).  % 749 samples
kind_height(box, 0.1338).  % 1,915 samples
kind_height(can, 0.1232).  % 543 samples
kind_height(cup, 0.1044).  % 1,497 samples
kind_height(mug, 0.1024).  % 1,630 samples

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
hides(ball, 0.001874).  % 13,339
hides(bottle, 9.749e-05).  % 10,255
hides(bowl, 0.1675).  % 11,034
hides(box, 0.2377).  % 30,454
hides(can, 0.0001273).  % 7,852
hides(cup, 0.08995).  % 18,875
hides(mug, 0.05801).  % 20,355
hides(skin, 0.4886).  % 4,513
hidden_share(ball, 0.2244).  % 45,964
hidden_share(bottle, 0.14).  % 1,584
hidden_share(bowl, 0.0123).  % 5,363
hidden_share(box, 0.02792).  % 8,522
hidden_share(can, 0.2177).  % 4,790
hidden_share(cup, 0.1359).  % 11,782
hidden_share(mug, 0.06116).  % 11,689
hidden_share(skin, 3.706e-05).  % 26,983
carries(skin, 0.9965).  % 1,154
carrier(skin).
can_occlude(O) := category(O, C), hides(C, P), P >= 0.01, \+ is_carrier(O).
is_carrier(O) := category(O, C), carrier(C).
hand_known := object(O), is_carrier(O).
can_be_occluded(A) := category(A, C), hidden_share(C, P), P >= 0.01.

:- include('too/too_learned_glue.pl').
% The onset reach (m): 90% of the 62 onsets in the data were within 0.1167 m; times 2.0.
onset_reach(0.2335).
% The reach of the kinds with onsets enough for one of their own.
onset_reach(bowl, 0.2396).  % 10 onsets, 90% within 0.1198 m
onset_reach(box, 0.2169).  % 34 onsets, 90% within 0.1084 m
onset_reach(mug, 0.0507).  % 10 onsets, 90% within 0.02535 m

% The learned rules (ddc learn): a distributional logic tree for occluder/2 (each path from its
% root to a leaf is one clause of the tree), with the background knowledge it reads.
learned_from(own, ['data_truth.pl'],
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

% occluder(Occluded, Occluder):t+1: 92 clauses, 28836 groundings, training log-likelihood -7558.29 (mean -0.118961 per grounding), 144 parameters.
occluder(Occluded, Occluder):t+1 ~ finite([P1:true, P2:false]) :=
    pair(Occluded, Occluder):t+1,
    (   distance(Occluded, Occluder):t+1 ~= Distance
    ->  (   kind(Occluder):t+1 ~= ball
        ->  (   moved(Occluder):t+1 ~= Moved
            ->  (   Moved < 0.004
                ->  % n = 662 (weight 2870), log-likelihood -0.999478, finite
                    P1 = 0.000348189,
                    P2 = 0.999651811
                ;   (   occluded_by(Occluded, Occluder):t
                    ->  % n = 16 (weight 20), log-likelihood -0.9304, finite
                        P1 = 0.9545455,
                        P2 = 0.0454545
                    ;   (   seen(Occluder):t
                        ->  % n = 593 (weight 729), log-likelihood -0.997947, finite
                            P1 = 0.00136799,
                            P2 = 0.99863201
                        ;   % n = 58 (weight 66), log-likelihood -11.7294, logistic
                            logistic([Distance], [-22.6013, 0.865311], P1),
                            P2 is 1-P1
                        )
                    )
                )
            ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                logistic([Distance], [-40.1325, -0.561127], P1),
                P2 is 1-P1
            )
        ;   kind(Occluder):t+1 ~= bottle
        ->  % n = 1473 (weight 6701), log-likelihood -0.999776, finite
            P1 = 0.000149187,
            P2 = 0.999850813
        ;   kind(Occluder):t+1 ~= bowl
        ->  (   occluded_by(Occluded, Occluder):t
            ->  (   rise(Occluded, Occluder):t+1 ~= Rise
                ->  (   Rise < 0.0
                    ->  % n = 149 (weight 489), log-likelihood -0.996942, finite
                        P1 = 0.99796334,
                        P2 = 0.00203666
                    ;   Rise < 0.1
                    ->  % n = 466 (weight 1310), log-likelihood -8.48311, finite
                        P1 = 0.99847561,
                        P2 = 0.00152439
                    ;   % n = 42 (weight 46), log-likelihood -21.2821, finite
                        P1 = 0.8125,
                        P2 = 0.1875
                    )
                ;   % n = 0, too few groundings for a model of its own: the parent's model, finite
                    P1 = 0.99458581,
                    P2 = 0.00541419
                )
            ;   (   kind(Occluded):t+1 ~= ball
                ->  (   rise(Occluded, Occluder):t+1 ~= Rise4
                    ->  (   Rise4 < 0.0
                        ->  (   moved(Occluder):t+1 ~= Moved3
                            ->  (   Moved3 < 0.004
                                ->  % n = 102 (weight 274), log-likelihood -0.27036, logistic
                                    logistic([Distance], [-1921.13, 46.8458], P1),
                                    P2 is 1-P1
                                ;   % n = 55 (weight 107), log-likelihood -64.1669, logistic
                                    logistic([Distance], [14.8954, -1.52019], P1),
                                    P2 is 1-P1
                                )
                            ;   % n = 0, too few groundings for a model of its own: the parent's model, finite
                                P1 = 0.263708,
                                P2 = 0.736292
                            )
                        ;   Rise4 < 0.1
                        ->  (   moved(Occluder):t+1 ~= Moved6
                            ->  (   Moved6 < 0.004
                                ->  % n = 1073 (weight 2437), log-likelihood -507.443, logistic
                                    logistic([Distance], [-45.5859, 2.22777], P1),
                                    P2 is 1-P1
                                ;   % n = 570 (weight 702), log-likelihood -306.951, logistic
                                    logistic([Distance], [-20.9486, 1.53693], P1),
                                    P2 is 1-P1
                                )
                            ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                                logistic([Distance], [-31.9267, 1.90565], P1),
                                P2 is 1-P1
                            )
                        ;   % n = 154 (weight 182), log-likelihood -71.8074, logistic
                            logistic([Distance], [-22.4684, 0.724655], P1),
                            P2 is 1-P1
                        )
                    ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                        logistic([Distance], [-26.5943, 1.21298], P1),
                        P2 is 1-P1
                    )
                ;   kind(Occluded):t+1 ~= bottle
                ->  % n = 31 (weight 47), log-likelihood -0.969106, finite
                    P1 = 0.0204082,
                    P2 = 0.9795918
                ;   kind(Occluded):t+1 ~= bowl
                ->  % n = 55 (weight 211), log-likelihood -0.992943, finite
                    P1 = 0.00469484,
                    P2 = 0.99530516
                ;   kind(Occluded):t+1 ~= box
                ->  % n = 168 (weight 376), log-likelihood -0.996027, finite
                    P1 = 0.0026455,
                    P2 = 0.9973545
                ;   kind(Occluded):t+1 ~= can
                ->  % n = 54 (weight 114), log-likelihood -0.987019, finite
                    P1 = 0.00862069,
                    P2 = 0.99137931
                ;   kind(Occluded):t+1 ~= cup
                ->  % n = 362 (weight 1054), log-likelihood -0.998579, finite
                    P1 = 0.00094697,
                    P2 = 0.99905303
                ;   kind(Occluded):t+1 ~= mug
                ->  % n = 384 (weight 920), log-likelihood -0.998372, finite
                    P1 = 0.0010846,
                    P2 = 0.9989154
                ;   kind(Occluded):t+1 ~= skin
                ->  % n = 199 (weight 531), log-likelihood -0.997183, finite
                    P1 = 0.00187617,
                    P2 = 0.99812383
                ;   \+ kind(Occluded):t+1 ~= _
                ->  % n = 0, too few groundings for a model of its own: the parent's model, logistic
                    logistic([Distance], [-35.3952, 1.10155], P1),
                    P2 is 1-P1
                )
            )
        ;   kind(Occluder):t+1 ~= box
        ->  (   kind(Occluded):t+1 ~= ball
            ->  (   occluded_by(Occluded, Occluder):t
                ->  (   moved(Occluder):t+1 ~= Moved9
                    ->  (   Moved9 < 0.004
                        ->  % n = 912 (weight 4556), log-likelihood -9.73061, finite
                            P1 = 0.999561211,
                            P2 = 0.000438789
                        ;   (   lift(Occluder):t+1 ~= Lift
                            ->  % n = 552 (weight 724), log-likelihood -77.9504, logistic
                                logistic([Distance, Lift], [75.1704, -79.3579, 3.22324], P1),
                                P2 is 1-P1
                            ;   % n = 0, too few groundings for a model of its own: the parent's model, finite
                                P1 = 0.9669421,
                                P2 = 0.0330579
                            )
                        )
                    ;   % n = 0, too few groundings for a model of its own: the parent's model, finite
                        P1 = 0.99526694,
                        P2 = 0.00473306
                    )
                ;   (   moved(Occluder):t+1 ~= Moved12
                    ->  (   Moved12 < 0.004
                        ->  % n = 3428 (weight 6100), log-likelihood -2166.82, logistic
                            logistic([Distance], [-34.2214, 1.69196], P1),
                            P2 is 1-P1
                        ;   (   rise(Occluded, Occluder):t+1 ~= Rise8
                            ->  (   Rise8 < 0.0
                                ->  % n = 4, too few groundings for a model of its own: the parent's model, log-likelihood -0.45361, logistic
                                    logistic([Distance], [-17.6837, 0.955888], P1),
                                    P2 is 1-P1
                                ;   Rise8 < 0.1
                                ->  % n = 999 (weight 1123), log-likelihood -602.52, logistic
                                    logistic([Distance], [-16.2103, 1.08424], P1),
                                    P2 is 1-P1
                                ;   % n = 293 (weight 305), log-likelihood -56.0366, logistic
                                    logistic([Distance], [-36.4905, 0.494207], P1),
                                    P2 is 1-P1
                                )
                            ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                                logistic([Distance], [-17.6837, 0.955888], P1),
                                P2 is 1-P1
                            )
                        )
                    ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                        logistic([Distance], [-28.3923, 1.54046], P1),
                        P2 is 1-P1
                    )
                )
            ;   kind(Occluded):t+1 ~= bottle
            ->  % n = 47 (weight 103), log-likelihood -0.985653, finite
                P1 = 0.00952381,
                P2 = 0.99047619
            ;   kind(Occluded):t+1 ~= bowl
            ->  % n = 112 (weight 332), log-likelihood -0.995503, finite
                P1 = 0.00299401,
                P2 = 0.99700599
            ;   kind(Occluded):t+1 ~= box
            ->  % n = 268 (weight 992), log-likelihood -0.99849, finite
                P1 = 0.00100604,
                P2 = 0.99899396
            ;   kind(Occluded):t+1 ~= can
            ->  (   rise(Occluded, Occluder):t+1 ~= Rise12
                ->  (   Rise12 < 0.0
                    ->  (   lift(Occluder):t+1 ~= Lift2
                        ->  % n = 139 (weight 207), log-likelihood -4.41698, logistic
                            logistic([Distance, Lift2], [-335.196, -635.573, 6.32556], P1),
                            P2 is 1-P1
                        ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                            logistic([Distance], [-134.678, 4.55349], P1),
                            P2 is 1-P1
                        )
                    ;   Rise12 < 0.1
                    ->  % n = 779 (weight 1339), log-likelihood -31.9967, logistic
                        logistic([Distance], [-79.8536, 6.23555], P1),
                        P2 is 1-P1
                    ;   % n = 27 (weight 35), log-likelihood -0.958964, finite
                        P1 = 0.027027,
                        P2 = 0.972973
                    )
                ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                    logistic([Distance], [-78.9292, 4.90099], P1),
                    P2 is 1-P1
                )
            ;   kind(Occluded):t+1 ~= cup
            ->  (   moved(Occluder):t+1 ~= Moved15
                ->  (   Moved15 < 0.004
                    ->  (   lost_anywhere(Occluded):t
                        ->  % n = 6 (weight 30), log-likelihood -0.952461, finite
                            P1 = 0.03125,
                            P2 = 0.96875
                        ;   (   seen(Occluded):t
                            ->  % n = 19, log-likelihood -0.927013, finite
                                P1 = 0.047619,
                                P2 = 0.952381
                            ;   % n = 1518 (weight 2962), log-likelihood -242.426, logistic
                                logistic([Distance], [-327.108, 16.1725], P1),
                                P2 is 1-P1
                            )
                        )
                    ;   % n = 277 (weight 349), log-likelihood -121.678, logistic
                        logistic([Distance], [-32.7242, 2.2475], P1),
                        P2 is 1-P1
                    )
                ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                    logistic([Distance], [-69.8903, 4.74906], P1),
                    P2 is 1-P1
                )
            ;   kind(Occluded):t+1 ~= mug
            ->  % n = 371 (weight 1179), log-likelihood -0.998729, finite
                P1 = 0.00084674,
                P2 = 0.99915326
            ;   kind(Occluded):t+1 ~= skin
            ->  % n = 492 (weight 1504), log-likelihood -0.999004, finite
                P1 = 0.000664011,
                P2 = 0.999335989
            ;   \+ kind(Occluded):t+1 ~= _
            ->  % n = 0, too few groundings for a model of its own: the parent's model, logistic
                logistic([Distance], [-47.9434, 2.74957], P1),
                P2 is 1-P1
            )
        ;   kind(Occluder):t+1 ~= can
        ->  % n = 886 (weight 3010), log-likelihood -0.999502, finite
            P1 = 0.000332005,
            P2 = 0.999667995
        ;   kind(Occluder):t+1 ~= cup
        ->  (   kind(Occluded):t+1 ~= ball
            ->  (   occluded_by(Occluded, Occluder):t
                ->  (   moved(Occluder):t+1 ~= Moved18
                    ->  (   Moved18 < 0.004
                        ->  % n = 257 (weight 1281), log-likelihood -8.46069, finite
                            P1 = 0.99844115,
                            P2 = 0.00155885
                        ;   % n = 289 (weight 413), log-likelihood -26.2951, logistic
                            logistic([Distance], [434.903, 1.86245], P1),
                            P2 is 1-P1
                        )
                    ;   % n = 0, too few groundings for a model of its own: the parent's model, finite
                        P1 = 0.99410377,
                        P2 = 0.00589623
                    )
                ;   (   moved(Occluder):t+1 ~= Moved21
                    ->  (   Moved21 < 0.004
                        ->  % n = 1807 (weight 4143), log-likelihood -1317.49, logistic
                            logistic([Distance], [-25.0743, 1.86791], P1),
                            P2 is 1-P1
                        ;   % n = 1063 (weight 1203), log-likelihood -547.294, logistic
                            logistic([Distance], [-19.1498, 1.58826], P1),
                            P2 is 1-P1
                        )
                    ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                        logistic([Distance], [-23.6162, 1.83253], P1),
                        P2 is 1-P1
                    )
                )
            ;   kind(Occluded):t+1 ~= bottle
            ->  % n = 37 (weight 129), log-likelihood -0.988511, finite
                P1 = 0.00763359,
                P2 = 0.99236641
            ;   kind(Occluded):t+1 ~= bowl
            ->  % n = 80 (weight 196), log-likelihood -0.992407, finite
                P1 = 0.00505051,
                P2 = 0.99494949
            ;   kind(Occluded):t+1 ~= box
            ->  % n = 138 (weight 438), log-likelihood -0.996587, finite
                P1 = 0.00227273,
                P2 = 0.99772727
            ;   kind(Occluded):t+1 ~= can
            ->  % n = 623 (weight 1535), log-likelihood -0.999024, finite
                P1 = 0.000650618,
                P2 = 0.999349382
            ;   kind(Occluded):t+1 ~= cup
            ->  % n = 143 (weight 351), log-likelihood -0.995745, finite
                P1 = 0.00283286,
                P2 = 0.99716714
            ;   kind(Occluded):t+1 ~= mug
            ->  % n = 181 (weight 657), log-likelihood -0.997722, finite
                P1 = 0.00151745,
                P2 = 0.99848255
            ;   kind(Occluded):t+1 ~= skin
            ->  % n = 211 (weight 699), log-likelihood -0.997859, finite
                P1 = 0.00142653,
                P2 = 0.99857347
            ;   \+ kind(Occluded):t+1 ~= _
            ->  % n = 0, too few groundings for a model of its own: the parent's model, logistic
                logistic([Distance], [-29.386, 2.02376], P1),
                P2 is 1-P1
            )
        ;   kind(Occluder):t+1 ~= mug
        ->  (   seen(Occluded):t
            ->  % n = 18, log-likelihood -11.4683, finite
                P1 = 0.35,
                P2 = 0.65
            ;   (   lift(Occluder):t+1 ~= Lift4
                ->  % n = 1821 (weight 3325), log-likelihood -299.634, logistic
                    logistic([Distance, Lift4], [-115.462, -196.223, 5.14432], P1),
                    P2 is 1-P1
                ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                    logistic([Distance], [-109.756, 4.96508], P1),
                    P2 is 1-P1
                )
            )
        ;   kind(Occluder):t+1 ~= skin
        ->  (   kind(Occluded):t+1 ~= ball
            ->  (   occluded_by(Occluded, Occluder):t
                ->  % n = 220 (weight 284), log-likelihood -6.94882, finite
                    P1 = 0.99300699,
                    P2 = 0.00699301
                ;   % n = 663 (weight 723), log-likelihood -208.904, logistic
                    logistic([Distance], [-30.3519, 2.36453], P1),
                    P2 is 1-P1
                )
            ;   kind(Occluded):t+1 ~= bottle
            ->  (   occluded_by(Occluded, Occluder):t
                ->  % n = 150 (weight 214), log-likelihood -15.911, finite
                    P1 = 0.9814815,
                    P2 = 0.0185185
                ;   (   moved(Occluder):t+1 ~= Moved24
                    ->  (   Moved24 < 0.004
                        ->  % n = 57, log-likelihood -0.974383, finite
                            P1 = 0.9830508,
                            P2 = 0.0169492
                        ;   % n = 140 (weight 144), log-likelihood -69.4997, finite
                            P1 = 0.808219,
                            P2 = 0.191781
                        )
                    ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                        logistic([Distance], [-13.1544, 2.46657], P1),
                        P2 is 1-P1
                    )
                )
            ;   kind(Occluded):t+1 ~= bowl
            ->  (   occluded_by(Occluded, Occluder):t
                ->  % n = 38 (weight 62), log-likelihood -5.40241, finite
                    P1 = 0.96875,
                    P2 = 0.03125
                ;   % n = 96 (weight 100), log-likelihood -68.9945, finite
                    P1 = 0.539216,
                    P2 = 0.460784
                )
            ;   kind(Occluded):t+1 ~= box
            ->  (   lift(Occluder):t+1 ~= Lift6
                ->  % n = 428 (weight 516), log-likelihood -161.609, logistic
                    logistic([Distance, Lift6], [-21.7589, -52.203, 3.2553], P1),
                    P2 is 1-P1
                ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                    logistic([Distance], [-19.2635, 2.99292], P1),
                    P2 is 1-P1
                )
            ;   kind(Occluded):t+1 ~= can
            ->  (   lift(Occluder):t+1 ~= Lift8
                ->  % n = 588 (weight 688), log-likelihood -150.292, logistic
                    logistic([Distance, Lift8], [-35.8024, -51.9539, 4.12431], P1),
                    P2 is 1-P1
                ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                    logistic([Distance], [-32.8235, 3.89524], P1),
                    P2 is 1-P1
                )
            ;   kind(Occluded):t+1 ~= cup
            ->  (   lift(Occluder):t+1 ~= Lift10
                ->  % n = 826 (weight 922), log-likelihood -64.669, logistic
                    logistic([Distance, Lift10], [-24.7086, -120.384, 6.21834], P1),
                    P2 is 1-P1
                ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                    logistic([Distance], [-17.9685, 4.69883], P1),
                    P2 is 1-P1
                )
            ;   kind(Occluded):t+1 ~= mug
            ->  (   lift(Occluder):t+1 ~= Lift12
                ->  (   moved(Occluder):t+1 ~= Moved27
                    ->  (   Moved27 < 0.004
                        ->  % n = 200 (weight 364), log-likelihood -17.9481, logistic
                            logistic([Distance, Lift12], [-65.1791, -1680.74, 7.91792], P1),
                            P2 is 1-P1
                        ;   % n = 967 (weight 1015), log-likelihood -242.686, logistic
                            logistic([Distance, Lift12], [-25.4301, -37.1746, 3.87045], P1),
                            P2 is 1-P1
                        )
                    ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                        logistic([Distance, Lift12], [-26.9277, -42.1925, 4.05813], P1),
                        P2 is 1-P1
                    )
                ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                    logistic([Distance], [-25.0323, 3.89837], P1),
                    P2 is 1-P1
                )
            ;   kind(Occluded):t+1 ~= skin
            ->  % n = 0, too few groundings for a model of its own: the parent's model, logistic
                logistic([Distance], [-26.1648, 3.57626], P1),
                P2 is 1-P1
            ;   \+ kind(Occluded):t+1 ~= _
            ->  % n = 0, too few groundings for a model of its own: the parent's model, logistic
                logistic([Distance], [-26.1648, 3.57626], P1),
                P2 is 1-P1
            )
        ;   \+ kind(Occluder):t+1 ~= _
        ->  % n = 0, too few groundings for a model of its own: the parent's model, logistic
            logistic([Distance], [-38.355, 2.5103], P1),
            P2 is 1-P1
        )
    ;   % n = 0, too few groundings for a model of its own: the parent's model, finite
        P1 = 0.391293,
        P2 = 0.608707
    ).

% When a hand lets go of what it carries (ddc learn, from the carries beside the data): a
% distributional logic tree for released/1, with the background knowledge it reads.
learned_from(own, ['data_truth.release.pl'],
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

% released(Held):t+1: 3 clauses, 2528 groundings, training log-likelihood -78.9072 (mean -0.0312133 per grounding), 6 parameters.
released(Held):t+1 ~ finite([P1:true, P2:false]) :=
    carried(Held):t+1,
    (   height(Held):t+1 ~= Height
    ->  (   highest(Held):t+1 ~= Highest
        ->  % n = 2528, log-likelihood -78.9072, logistic
            logistic([Height, Highest], [-100.738, 66.9638, -9.84724], P1),
            P2 is 1-P1
        ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
            logistic([Height], [-43.1725, -1.5941], P1),
            P2 is 1-P1
        )
    ;   % n = 0, too few groundings for a model of its own: the parent's model, finite
        P1 = 0.0249012,
        P2 = 0.9750988
    ).

:- include('too/too_motion.pl').
