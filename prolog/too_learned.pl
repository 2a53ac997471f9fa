/*  too_learned.pl -- the theory of occlusion with rules learned from experience.

    Written by `anchoring learn-theory`: a tree learned (ddc learn) from
    data_truth.pl: 63861 groundings of occluder(A, O):t+1,
    70 clauses, training log-likelihood -25205.3;
    and one for released(A):t+1 from 1928 frames a hand held an object
    (3 clauses, training log-likelihood -70.2959);
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
obs_var(2.377e-06).  % the measurement noise of a perceived position (m², per axis); 87,816 samples
motion_var(2.595e-05).  % how far a perceived object moves in a frame (m², per axis); 102,633 samples
reappear_var(0.003261).  % where a hidden object is seen again, around its belief (m²); 492 samples
lost_var(0.0664).  % the same for an object lost while the camera saw nothing (m²); 6,854 samples
follow_keep(0.9556).  % the fraction of its offset from its occluder a hidden object keeps; 12,844 samples
follow_var(3.008e-06).  % the jitter of that offset per frame (m²); 12,844 samples
coast_keep(0.9643).  % the fraction of its velocity a hidden object under nothing keeps; 27,694 samples
wander_var(1.096e-06).  % how far such an object may move besides (m²); 27,694 samples
grip_reach(0.1018).  % how far (table plane) a hand's grip may be from what it takes (m); 38 samples
grip_height(0.1281).  % how far above it (m); 38 samples
occluder_rise(0.01008).  % how far below its centre (m; negative: above); 38 samples
grip_drop(0.01771).  % how far what a hand holds is below its grip (m); 1,928 samples
grip_rise(0.00179).  % how far a hand's grip rises in a frame when it lifts (m); 538 samples

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
hides(ball, 0.000409).  % 17,115
hides(box, 0.1175).  % 33,417
hides(can, 8.074e-05).  % 12,384
hides(cup, 0.1176).  % 32,401
hides(mug, 0.1104).  % 32,372
hides(skin, 0.4688).  % 4,554
hidden_share(ball, 0.2026).  % 50,647
hidden_share(box, 7.912e-05).  % 12,637
hidden_share(can, 0.1151).  % 25,126
hidden_share(cup, 6.968e-05).  % 14,349
hidden_share(mug, 0.03581).  % 8,320
hidden_share(skin, 4.725e-05).  % 21,164
carries(box, 0.25).  % 2
carries(cup, 0.3333).  % 1
carries(skin, 0.9918).  % 1,220
carrier(skin).
can_occlude(O) := category(O, C), hides(C, P), P >= 0.01, \+ is_carrier(O).
is_carrier(O) := category(O, C), carrier(C).
hand_known := object(O), is_carrier(O).
can_be_occluded(A) := category(A, C), hidden_share(C, P), P >= 0.01.

:- include('too/too_learned_glue.pl').
% The onset reach (m): 90% of the 58 onsets in the data were within 0.0406 m; times 2.0.
onset_reach(0.0812).

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
      type(kind(obj):t+1),
      rv(occluder(_, _):t+1, boolean),
      rv(distance(_, _):t+1, continuous),
      rv(distance3(_, _):t+1, continuous),
      rv(rise(_, _):t+1, continuous),
      rv(lift(_):t+1, continuous),
      rv(kind(_):t+1, discrete([ball, box, can, cup, mug, skin])),
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
kind(A):t+1 ~ val(C) :=
    category(A, C).

% occluder(Occluded, Occluder):t+1: 70 clauses, 63861 groundings, training log-likelihood -25205.3 (mean -0.138414 per grounding), 112 parameters.
occluder(Occluded, Occluder):t+1 ~ finite([P1:true, P2:false]) :=
    pair(Occluded, Occluder):t+1,
    (   occluded_by(Occluded, Occluder):t
    ->  (   lift(Occluder):t+1 ~= Lift
        ->  (   kind(Occluder):t+1 ~= ball
            ->  % n = 0, too few groundings for a model of its own: the parent's model, logistic
                logistic([Lift], [-76.9098, 5.07428], P1),
                P2 is 1-P1
            ;   kind(Occluder):t+1 ~= box
            ->  (   distance(Occluded, Occluder):t+1 ~= Distance
                ->  % n = 1119 (weight 3927), log-likelihood -123.443, logistic
                    logistic([Lift, Distance], [-446.7, 844.796, 5.3287], P1),
                    P2 is 1-P1
                ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                    logistic([Lift], [-312.408, 5.34929], P1),
                    P2 is 1-P1
                )
            ;   kind(Occluder):t+1 ~= can
            ->  % n = 0, too few groundings for a model of its own: the parent's model, logistic
                logistic([Lift], [-76.9098, 5.07428], P1),
                P2 is 1-P1
            ;   kind(Occluder):t+1 ~= cup
            ->  % n = 1164 (weight 3804), log-likelihood -105.384, logistic
                logistic([Lift], [-119.282, 5.52355], P1),
                P2 is 1-P1
            ;   kind(Occluder):t+1 ~= mug
            ->  (   distance(Occluded, Occluder):t+1 ~= Distance2
                ->  % n = 998 (weight 3570), log-likelihood -84.8291, logistic
                    logistic([Lift, Distance2], [-389.749, 689.662, 5.10854], P1),
                    P2 is 1-P1
                ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                    logistic([Lift], [-188.759, 5.49195], P1),
                    P2 is 1-P1
                )
            ;   kind(Occluder):t+1 ~= skin
            ->  % n = 1490 (weight 2126), log-likelihood -176.552, logistic
                logistic([Lift], [-52.3047, 4.35799], P1),
                P2 is 1-P1
            ;   \+ kind(Occluder):t+1 ~= _
            ->  % n = 0, too few groundings for a model of its own: the parent's model, logistic
                logistic([Lift], [-76.9098, 5.07428], P1),
                P2 is 1-P1
            )
        ;   % n = 0, too few groundings for a model of its own: the parent's model, finite
            P1 = 0.99084072,
            P2 = 0.00915928
        )
    ;   (   distance(Occluded, Occluder):t+1 ~= Distance4
        ->  (   kind(Occluder):t+1 ~= ball
            ->  (   seen(Occluder):t
                ->  % n = 5566 (weight 20650), log-likelihood -0.999927, finite
                    P1 = 4.84215e-5,
                    P2 = 0.9999515785
                ;   (   lift(Occluder):t+1 ~= Lift2
                    ->  % n = 196 (weight 276), log-likelihood -31.0311, logistic
                        logistic([Distance4, Lift2], [-3.48301, 45.2234, -2.7762], P1),
                        P2 is 1-P1
                    ;   % n = 0, too few groundings for a model of its own: the parent's model, finite
                        P1 = 0.0467626,
                        P2 = 0.9532374
                    )
                )
            ;   kind(Occluder):t+1 ~= box
            ->  (   kind(Occluded):t+1 ~= ball
                ->  (   rise(Occluded, Occluder):t+1 ~= Rise
                    ->  (   Rise < 0.0
                        ->  % n = 0, too few groundings for a model of its own: the parent's model, logistic
                            logistic([Distance4], [-13.6774, 0.269046], P1),
                            P2 is 1-P1
                        ;   Rise < 0.1
                        ->  (   seen(Occluded):t
                            ->  % n = 114, log-likelihood -0.987019, finite
                                P1 = 0.00862069,
                                P2 = 0.99137931
                            ;   (   lost_anywhere(Occluded):t
                                ->  % n = 55 (weight 247), log-likelihood -1.23131, logistic
                                    logistic([Distance4], [-40.3902, 3.97825], P1),
                                    P2 is 1-P1
                                ;   % n = 7071 (weight 20839), log-likelihood -4502.66, logistic
                                    logistic([Distance4], [-13.5582, 0.303063], P1),
                                    P2 is 1-P1
                                )
                            )
                        ;   (   lift(Occluder):t+1 ~= Lift4
                            ->  % n = 515 (weight 699), log-likelihood -85.713, logistic
                                logistic([Distance4, Lift4], [-22.7454, -40.874, -0.154984], P1),
                                P2 is 1-P1
                            ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                                logistic([Distance4], [-19.4787, -0.475447], P1),
                                P2 is 1-P1
                            )
                        )
                    ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                        logistic([Distance4], [-13.6774, 0.269046], P1),
                        P2 is 1-P1
                    )
                ;   kind(Occluded):t+1 ~= box
                ->  % n = 1374 (weight 4002), log-likelihood -0.999625, finite
                    P1 = 0.00024975,
                    P2 = 0.99975025
                ;   kind(Occluded):t+1 ~= can
                ->  (   rise(Occluded, Occluder):t+1 ~= Rise4
                    ->  (   Rise4 < 0.0
                        ->  % n = 471 (weight 955), log-likelihood -26.3998, logistic
                            logistic([Distance4], [-55.6664, 4.23835], P1),
                            P2 is 1-P1
                        ;   Rise4 < 0.1
                        ->  (   lost_anywhere(Occluded):t
                            ->  % n = 63 (weight 159), log-likelihood -12.0234, logistic
                                logistic([Distance4], [-19.6314, 0.509587], P1),
                                P2 is 1-P1
                            ;   % n = 2153 (weight 4965), log-likelihood -2085.91, logistic
                                logistic([Distance4], [-8.99996, 0.682798], P1),
                                P2 is 1-P1
                            )
                        ;   % n = 402 (weight 478), log-likelihood -48.6087, finite
                            P1 = 0.0229167,
                            P2 = 0.9770833
                        )
                    ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                        logistic([Distance4], [-11.3496, 0.992303], P1),
                        P2 is 1-P1
                    )
                ;   kind(Occluded):t+1 ~= cup
                ->  % n = 1112 (weight 3748), log-likelihood -0.9996, finite
                    P1 = 0.000266667,
                    P2 = 0.999733333
                ;   kind(Occluded):t+1 ~= mug
                ->  % n = 1214 (weight 3290), log-likelihood -25.037, logistic
                    logistic([Distance4], [-154.774, 4.64838], P1),
                    P2 is 1-P1
                ;   kind(Occluded):t+1 ~= skin
                ->  % n = 1446 (weight 4582), log-likelihood -0.999673, finite
                    P1 = 0.00021815,
                    P2 = 0.99978185
                ;   \+ kind(Occluded):t+1 ~= _
                ->  % n = 0, too few groundings for a model of its own: the parent's model, logistic
                    logistic([Distance4], [-13.2399, -0.0548848], P1),
                    P2 is 1-P1
                )
            ;   kind(Occluder):t+1 ~= can
            ->  % n = 3762 (weight 15490), log-likelihood -0.999903, finite
                P1 = 6.45494e-5,
                P2 = 0.9999354506
            ;   kind(Occluder):t+1 ~= cup
            ->  (   kind(Occluded):t+1 ~= ball
                ->  (   lost_anywhere(Occluded):t
                    ->  (   seen(Occluder):t
                        ->  % n = 41 (weight 197), log-likelihood -0.992445, finite
                            P1 = 0.00502513,
                            P2 = 0.99497487
                        ;   % n = 13 (weight 25), log-likelihood -13.8015, finite
                            P1 = 0.259259,
                            P2 = 0.740741
                        )
                    ;   (   seen(Occluded):t
                        ->  % n = 118, log-likelihood -9.0791, logistic
                            logistic([Distance4], [-41.9972, 2.30251], P1),
                            P2 is 1-P1
                        ;   (   rise(Occluded, Occluder):t+1 ~= Rise8
                            ->  (   Rise8 < 0.0
                                ->  % n = 353 (weight 905), log-likelihood -387.737, logistic
                                    logistic([Distance4], [-8.05152, -0.0263108], P1),
                                    P2 is 1-P1
                                ;   Rise8 < 0.1
                                ->  % n = 7159 (weight 18419), log-likelihood -7860.27, logistic
                                    logistic([Distance4], [-5.0341, -0.451174], P1),
                                    P2 is 1-P1
                                ;   % n = 418 (weight 478), log-likelihood -87.5141, logistic
                                    logistic([Distance4], [-10.7366, -0.669748], P1),
                                    P2 is 1-P1
                                )
                            ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                                logistic([Distance4], [-5.15066, -0.452483], P1),
                                P2 is 1-P1
                            )
                        )
                    )
                ;   kind(Occluded):t+1 ~= box
                ->  % n = 648 (weight 2304), log-likelihood -0.999349, finite
                    P1 = 0.000433651,
                    P2 = 0.999566349
                ;   kind(Occluded):t+1 ~= can
                ->  % n = 2430 (weight 9070), log-likelihood -0.999835, finite
                    P1 = 0.000110229,
                    P2 = 0.999889771
                ;   kind(Occluded):t+1 ~= cup
                ->  % n = 979 (weight 3291), log-likelihood -0.999544, finite
                    P1 = 0.000303674,
                    P2 = 0.999696326
                ;   kind(Occluded):t+1 ~= mug
                ->  % n = 484 (weight 1596), log-likelihood -0.999061, finite
                    P1 = 0.000625782,
                    P2 = 0.999374218
                ;   kind(Occluded):t+1 ~= skin
                ->  % n = 1410 (weight 4998), log-likelihood -0.9997, finite
                    P1 = 0.0002,
                    P2 = 0.9998
                ;   \+ kind(Occluded):t+1 ~= _
                ->  % n = 0, too few groundings for a model of its own: the parent's model, logistic
                    logistic([Distance4], [-6.68081, -0.909845], P1),
                    P2 is 1-P1
                )
            ;   kind(Occluder):t+1 ~= mug
            ->  (   kind(Occluded):t+1 ~= ball
                ->  (   rise(Occluded, Occluder):t+1 ~= Rise12
                    ->  (   Rise12 < 0.0
                        ->  % n = 193 (weight 645), log-likelihood -7.33232, logistic
                            logistic([Distance4], [19.902, -12.6057], P1),
                            P2 is 1-P1
                        ;   Rise12 < 0.1
                        ->  (   lost_anywhere(Occluded):t
                            ->  % n = 121 (weight 389), log-likelihood -4.94206, logistic
                                logistic([Distance4], [-28.6839, 1.90042], P1),
                                P2 is 1-P1
                            ;   (   seen(Occluded):t
                                ->  % n = 93, log-likelihood -7.52216, logistic
                                    logistic([Distance4], [-27.187, 2.06956], P1),
                                    P2 is 1-P1
                                ;   % n = 7348 (weight 18260), log-likelihood -7320.25, logistic
                                    logistic([Distance4], [-7.65045, 0.111207], P1),
                                    P2 is 1-P1
                                )
                            )
                        ;   % n = 341 (weight 409), log-likelihood -42.6782, logistic
                            logistic([Distance4], [-15.4096, -0.419017], P1),
                            P2 is 1-P1
                        )
                    ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                        logistic([Distance4], [-8.00257, 0.099568], P1),
                        P2 is 1-P1
                    )
                ;   kind(Occluded):t+1 ~= box
                ->  % n = 1176 (weight 3392), log-likelihood -0.999558, finite
                    P1 = 0.000294638,
                    P2 = 0.999705362
                ;   kind(Occluded):t+1 ~= can
                ->  % n = 2267 (weight 7763), log-likelihood -0.999807, finite
                    P1 = 0.000128783,
                    P2 = 0.999871217
                ;   kind(Occluded):t+1 ~= cup
                ->  % n = 1101 (weight 3737), log-likelihood -0.999599, finite
                    P1 = 0.000267451,
                    P2 = 0.999732549
                ;   kind(Occluded):t+1 ~= mug
                ->  % n = 735 (weight 2027), log-likelihood -0.999261, finite
                    P1 = 0.000492854,
                    P2 = 0.999507146
                ;   kind(Occluded):t+1 ~= skin
                ->  % n = 1419 (weight 4627), log-likelihood -0.999676, finite
                    P1 = 0.000216029,
                    P2 = 0.999783971
                ;   \+ kind(Occluded):t+1 ~= _
                ->  % n = 0, too few groundings for a model of its own: the parent's model, logistic
                    logistic([Distance4], [-9.87146, -0.280181], P1),
                    P2 is 1-P1
                )
            ;   kind(Occluder):t+1 ~= skin
            ->  (   kind(Occluded):t+1 ~= ball
                ->  % n = 2059 (weight 2511), log-likelihood -1466.78, logistic
                    logistic([Distance4], [-3.47721, 0.092319], P1),
                    P2 is 1-P1
                ;   kind(Occluded):t+1 ~= box
                ->  % n = 319 (weight 423), log-likelihood -0.996467, finite
                    P1 = 0.00235294,
                    P2 = 0.99764706
                ;   kind(Occluded):t+1 ~= can
                ->  (   lift(Occluder):t+1 ~= Lift6
                    ->  (   rise(Occluded, Occluder):t+1 ~= Rise16
                        ->  (   Rise16 < 0.0
                            ->  % n = 30 (weight 38), log-likelihood -0.962077, finite
                                P1 = 0.025,
                                P2 = 0.975
                            ;   Rise16 < 0.1
                            ->  % n = 598 (weight 602), log-likelihood -179.859, logistic
                                logistic([Distance4, Lift6], [-6.9022, -91.6123, 4.20956], P1),
                                P2 is 1-P1
                            ;   (   lost_anywhere(Occluded):t
                                ->  % n = 28, log-likelihood -9.62223, finite
                                    P1 = 0.133333,
                                    P2 = 0.866667
                                ;   % n = 1139 (weight 1159), log-likelihood -478.125, logistic
                                    logistic([Distance4, Lift6], [-6.66907, -26.9532, 3.55097], P1),
                                    P2 is 1-P1
                                )
                            )
                        ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                            logistic([Distance4, Lift6], [-6.29963, -28.6624, 3.37805], P1),
                            P2 is 1-P1
                        )
                    ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                        logistic([Distance4], [-5.74118, 3.09609], P1),
                        P2 is 1-P1
                    )
                ;   kind(Occluded):t+1 ~= cup
                ->  % n = 365 (weight 457), log-likelihood -0.996729, finite
                    P1 = 0.00217865,
                    P2 = 0.99782135
                ;   kind(Occluded):t+1 ~= mug
                ->  % n = 191 (weight 219), log-likelihood -0.993199, finite
                    P1 = 0.00452489,
                    P2 = 0.99547511
                ;   kind(Occluded):t+1 ~= skin
                ->  % n = 0, too few groundings for a model of its own: the parent's model, logistic
                    logistic([Distance4], [-3.27759, 0.504332], P1),
                    P2 is 1-P1
                ;   \+ kind(Occluded):t+1 ~= _
                ->  % n = 0, too few groundings for a model of its own: the parent's model, logistic
                    logistic([Distance4], [-3.27759, 0.504332], P1),
                    P2 is 1-P1
                )
            ;   \+ kind(Occluder):t+1 ~= _
            ->  % n = 0, too few groundings for a model of its own: the parent's model, logistic
                logistic([Distance4], [-8.88638, -0.547184], P1),
                P2 is 1-P1
            )
        ;   % n = 0, too few groundings for a model of its own: the parent's model, finite
            P1 = 0.0774147,
            P2 = 0.9225853
        )
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

% released(Held):t+1: 3 clauses, 1928 groundings, training log-likelihood -70.2959 (mean -0.0364605 per grounding), 6 parameters.
released(Held):t+1 ~ finite([P1:true, P2:false]) :=
    carried(Held):t+1,
    (   height(Held):t+1 ~= Height
    ->  (   highest(Held):t+1 ~= Highest
        ->  % n = 1928, log-likelihood -70.2959, logistic
            logistic([Height, Highest], [-90.9747, 32.2868, -4.7466], P1),
            P2 is 1-P1
        ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
            logistic([Height], [-74.8804, -1.1015], P1),
            P2 is 1-P1
        )
    ;   % n = 0, too few groundings for a model of its own: the parent's model, finite
        P1 = 0.0243523,
        P2 = 0.9756477
    ).

:- include('too/too_motion.pl').
