/*  too_learned.pl -- the theory of occlusion with rules learned from experience.

    Written by `anchoring learn-theory`: a tree learned (ddc learn) from
    data_truth.pl: 81779 groundings of occluder(A, O):t+1,
    63 clauses, training log-likelihood -28363.5;
    and one for released(A):t+1 from 2953 frames a hand held an object
    (3 clauses, training log-likelihood -120.556);
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
obs_var(4.411e-06).  % the measurement noise of a perceived position (m², per axis); 118,969 samples
motion_var(2.987e-05).  % how far a perceived object moves in a frame (m², per axis); 138,522 samples
reappear_var(0.001738).  % where a hidden object is seen again, around its belief (m²); 1,406 samples
lost_var(0.07437).  % the same for an object lost while the camera saw nothing (m²); 9,313 samples
follow_keep(0.9296).  % the fraction of its offset from its occluder a hidden object keeps; 19,339 samples
follow_var(5.969e-06).  % the jitter of that offset per frame (m²); 19,339 samples
coast_keep(0.8987).  % the fraction of its velocity a hidden object under nothing keeps; 208 samples
wander_var(0.0002156).  % how far such an object may move besides (m²); 208 samples
grip_reach(0.09242).  % how far (table plane) a hand's grip may be from what it takes (m); 60 samples
grip_height(0.13).  % how far above it (m); 60 samples
occluder_rise(0.004228).  % how far below its centre (m); 60 samples
grip_drop(0.01903).  % how far what a hand holds is below its grip (m); 2,892 samples
grip_rise(0.001788).  % how far a hand's grip rises in a frame when it lifts (m); 838 samples

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
hides(ball, 0.0001155).  % 17,312
hides(box, 0.1509).  % 39,306
hides(can, 8.384e-05).  % 11,926
hides(cup, 0.1962).  % 37,543
hides(mug, 0.12).  % 33,187
hides(skin, 0.4402).  % 5,879
hidden_share(ball, 0.2432).  % 58,325
hidden_share(box, 0.03502).  % 7,908
hidden_share(can, 0.244).  % 9,248
hidden_share(cup, 0.1078).  % 13,087
hidden_share(mug, 0.1284).  % 13,562
hidden_share(skin, 2.324e-05).  % 43,023
carries(box, 0.3333).  % 1
carries(skin, 0.998).  % 1,511
carrier(skin).
can_occlude(O) := category(O, C), hides(C, P), P >= 0.01, \+ is_carrier(O).
is_carrier(O) := category(O, C), carrier(C).
hand_known := object(O), is_carrier(O).
can_be_occluded(A) := category(A, C), hidden_share(C, P), P >= 0.01.

:- include('too/too_learned_glue.pl').
% The onset reach (m): 90% of the 72 onsets in the data were within 0.04571 m; times 2.0.
onset_reach(0.0914).

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

% occluder(Occluded, Occluder):t+1: 63 clauses, 81779 groundings, training log-likelihood -28363.5 (mean -0.129884 per grounding), 101 parameters.
occluder(Occluded, Occluder):t+1 ~ finite([P1:true, P2:false]) :=
    pair(Occluded, Occluder):t+1,
    (   distance(Occluded, Occluder):t+1 ~= Distance
    ->  (   occluded_by(Occluded, Occluder):t
        ->  (   lift(Occluder):t+1 ~= Lift
            ->  % n = 6822 (weight 19818), log-likelihood -436.649, logistic
                logistic([Distance, Lift], [291.18, -144.606, 5.65716], P1),
                P2 is 1-P1
            ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                logistic([Distance], [190.017, 4.93943], P1),
                P2 is 1-P1
            )
        ;   (   kind(Occluder):t+1 ~= ball
            ->  (   seen(Occluder):t
                ->  % n = 6244 (weight 21412), log-likelihood -0.99993, finite
                    P1 = 4.66984e-5,
                    P2 = 0.9999533016
                ;   % n = 137 (weight 177), log-likelihood -11.1354, finite
                    P1 = 0.0167598,
                    P2 = 0.9832402
                )
            ;   kind(Occluder):t+1 ~= box
            ->  (   kind(Occluded):t+1 ~= ball
                ->  % n = 9762 (weight 28454), log-likelihood -1996.72, logistic
                    logistic([Distance], [-36.8072, 1.6893], P1),
                    P2 is 1-P1
                ;   kind(Occluded):t+1 ~= box
                ->  % n = 330 (weight 1038), log-likelihood -0.998557, finite
                    P1 = 0.000961538,
                    P2 = 0.999038462
                ;   kind(Occluded):t+1 ~= can
                ->  (   rise(Occluded, Occluder):t+1 ~= Rise
                    ->  (   Rise < 0.0
                        ->  % n = 129 (weight 233), log-likelihood -135.824, logistic
                            logistic([Distance], [-2.1877, 0.139988], P1),
                            P2 is 1-P1
                        ;   Rise < 0.1
                        ->  % n = 2261 (weight 3937), log-likelihood -2484.18, logistic
                            logistic([Distance], [-4.53844, 0.516325], P1),
                            P2 is 1-P1
                        ;   % n = 33 (weight 37), log-likelihood -14.7047, finite
                            P1 = 0.153846,
                            P2 = 0.846154
                        )
                    ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                        logistic([Distance], [-4.04262, 0.44025], P1),
                        P2 is 1-P1
                    )
                ;   kind(Occluded):t+1 ~= cup
                ->  (   rise(Occluded, Occluder):t+1 ~= Rise4
                    ->  (   Rise4 < 0.0
                        ->  % n = 75 (weight 131), log-likelihood -0.988684, finite
                            P1 = 0.0075188,
                            P2 = 0.9924812
                        ;   Rise4 < 0.1
                        ->  (   seen(Occluder):t
                            ->  % n = 1327 (weight 3711), log-likelihood -1139.99, logistic
                                logistic([Distance], [-10.9093, 0.21974], P1),
                                P2 is 1-P1
                            ;   % n = 49 (weight 89), log-likelihood -9.74097, finite
                                P1 = 0.032967,
                                P2 = 0.967033
                            )
                        ;   % n = 90 (weight 154), log-likelihood -0.990357, finite
                            P1 = 0.00641026,
                            P2 = 0.99358974
                        )
                    ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                        logistic([Distance], [-11.1077, 0.127667], P1),
                        P2 is 1-P1
                    )
                ;   kind(Occluded):t+1 ~= mug
                ->  (   rise(Occluded, Occluder):t+1 ~= Rise8
                    ->  (   Rise8 < 0.0
                        ->  % n = 88 (weight 216), log-likelihood -0.993105, finite
                            P1 = 0.00458716,
                            P2 = 0.99541284
                        ;   Rise8 < 0.1
                        ->  (   lost_anywhere(Occluded):t
                            ->  % n = 37 (weight 165), log-likelihood -6.40077, finite
                                P1 = 0.011976,
                                P2 = 0.988024
                            ;   (   seen(Occluder):t
                                ->  % n = 1895 (weight 4147), log-likelihood -1451.51, logistic
                                    logistic([Distance], [-13.0363, 0.983221], P1),
                                    P2 is 1-P1
                                ;   % n = 95 (weight 163), log-likelihood -91.9382, finite
                                    P1 = 0.254545,
                                    P2 = 0.745455
                                )
                            )
                        ;   % n = 185 (weight 245), log-likelihood -0.993916, finite
                            P1 = 0.00404858,
                            P2 = 0.99595142
                        )
                    ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                        logistic([Distance], [-12.7155, 0.667135], P1),
                        P2 is 1-P1
                    )
                ;   kind(Occluded):t+1 ~= skin
                ->  % n = 3270 (weight 11002), log-likelihood -0.999864, finite
                    P1 = 9.0876e-5,
                    P2 = 0.999909124
                ;   \+ kind(Occluded):t+1 ~= _
                ->  % n = 0, too few groundings for a model of its own: the parent's model, logistic
                    logistic([Distance], [-15.3674, 0.625193], P1),
                    P2 is 1-P1
                )
            ;   kind(Occluder):t+1 ~= can
            ->  % n = 4594 (weight 18250), log-likelihood -0.999918, finite
                P1 = 5.47885e-5,
                P2 = 0.9999452115
            ;   kind(Occluder):t+1 ~= cup
            ->  (   kind(Occluded):t+1 ~= ball
                ->  (   rise(Occluded, Occluder):t+1 ~= Rise12
                    ->  (   Rise12 < 0.0
                        ->  % n = 129 (weight 341), log-likelihood -30.2584, finite
                            P1 = 0.0204082,
                            P2 = 0.9795918
                        ;   Rise12 < 0.1
                        ->  (   seen(Occluder):t
                            ->  (   seen(Occluded):t
                                ->  % n = 107, log-likelihood -4.95344, logistic
                                    logistic([Distance], [-34.5712, 2.6258], P1),
                                    P2 is 1-P1
                                ;   % n = 11724 (weight 23156), log-likelihood -10735.2, logistic
                                    logistic([Distance], [-9.26563, 1.21661], P1),
                                    P2 is 1-P1
                                )
                            ;   % n = 291 (weight 763), log-likelihood -128.613, logistic
                                logistic([Distance], [-12.6584, -0.0675005], P1),
                                P2 is 1-P1
                            )
                        ;   % n = 278 (weight 310), log-likelihood -68.2388, logistic
                            logistic([Distance], [-18.0225, 0.5978], P1),
                            P2 is 1-P1
                        )
                    ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                        logistic([Distance], [-9.37732, 1.16175], P1),
                        P2 is 1-P1
                    )
                ;   kind(Occluded):t+1 ~= box
                ->  % n = 876 (weight 2376), log-likelihood -0.999369, finite
                    P1 = 0.000420521,
                    P2 = 0.999579479
                ;   kind(Occluded):t+1 ~= can
                ->  % n = 1437 (weight 4533), log-likelihood -0.999669, finite
                    P1 = 0.000220507,
                    P2 = 0.999779493
                ;   kind(Occluded):t+1 ~= cup
                ->  % n = 704 (weight 2468), log-likelihood -0.999393, finite
                    P1 = 0.000404858,
                    P2 = 0.999595142
                ;   kind(Occluded):t+1 ~= mug
                ->  % n = 1467 (weight 5283), log-likelihood -0.999716, finite
                    P1 = 0.000189215,
                    P2 = 0.999810785
                ;   kind(Occluded):t+1 ~= skin
                ->  % n = 3542 (weight 10602), log-likelihood -0.999859, finite
                    P1 = 9.4304e-5,
                    P2 = 0.999905696
                ;   \+ kind(Occluded):t+1 ~= _
                ->  % n = 0, too few groundings for a model of its own: the parent's model, logistic
                    logistic([Distance], [-11.2021, 0.902542], P1),
                    P2 is 1-P1
                )
            ;   kind(Occluder):t+1 ~= mug
            ->  (   kind(Occluded):t+1 ~= ball
                ->  (   rise(Occluded, Occluder):t+1 ~= Rise16
                    ->  (   Rise16 < 0.0
                        ->  % n = 194 (weight 318), log-likelihood -3.64438, logistic
                            logistic([Distance], [-43.3717, 5.79207], P1),
                            P2 is 1-P1
                        ;   Rise16 < 0.1
                        ->  % n = 9585 (weight 24145), log-likelihood -6783.2, logistic
                            logistic([Distance], [-14.6964, 1.23156], P1),
                            P2 is 1-P1
                        ;   % n = 143 (weight 175), log-likelihood -8.42973, logistic
                            logistic([Distance], [-12.7235, -1.21458], P1),
                            P2 is 1-P1
                        )
                    ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                        logistic([Distance], [-14.8787, 1.26339], P1),
                        P2 is 1-P1
                    )
                ;   kind(Occluded):t+1 ~= box
                ->  % n = 755 (weight 2347), log-likelihood -0.999361, finite
                    P1 = 0.000425713,
                    P2 = 0.999574287
                ;   kind(Occluded):t+1 ~= can
                ->  % n = 1140 (weight 3836), log-likelihood -0.999609, finite
                    P1 = 0.000260552,
                    P2 = 0.999739448
                ;   kind(Occluded):t+1 ~= cup
                ->  % n = 1387 (weight 4543), log-likelihood -0.99967, finite
                    P1 = 0.000220022,
                    P2 = 0.999779978
                ;   kind(Occluded):t+1 ~= mug
                ->  % n = 607 (weight 1775), log-likelihood -0.999156, finite
                    P1 = 0.000562746,
                    P2 = 0.999437254
                ;   kind(Occluded):t+1 ~= skin
                ->  % n = 2841 (weight 9637), log-likelihood -0.999844, finite
                    P1 = 0.000103745,
                    P2 = 0.999896255
                ;   \+ kind(Occluded):t+1 ~= _
                ->  % n = 0, too few groundings for a model of its own: the parent's model, logistic
                    logistic([Distance], [-16.5371, 1.0497], P1),
                    P2 is 1-P1
                )
            ;   kind(Occluder):t+1 ~= skin
            ->  (   kind(Occluded):t+1 ~= ball
                ->  (   rise(Occluded, Occluder):t+1 ~= Rise20
                    ->  (   Rise20 < 0.0
                        ->  % n = 0, too few groundings for a model of its own: the parent's model, logistic
                            logistic([Distance], [-13.3887, 0.642947], P1),
                            P2 is 1-P1
                        ;   Rise20 < 0.1
                        ->  % n = 915 (weight 1091), log-likelihood -375.64, logistic
                            logistic([Distance], [-10.5417, 0.589853], P1),
                            P2 is 1-P1
                        ;   % n = 2938 (weight 3578), log-likelihood -827.945, logistic
                            logistic([Distance], [-14.95, 0.720107], P1),
                            P2 is 1-P1
                        )
                    ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                        logistic([Distance], [-13.3887, 0.642947], P1),
                        P2 is 1-P1
                    )
                ;   kind(Occluded):t+1 ~= box
                ->  (   seen(Occluded):t
                    ->  % n = 54, log-likelihood -4.22026, logistic
                        logistic([Distance], [-40.3323, 3.20919], P1),
                        P2 is 1-P1
                    ;   % n = 391 (weight 419), log-likelihood -244.481, logistic
                        logistic([Distance], [-4.1439, 1.47515], P1),
                        P2 is 1-P1
                    )
                ;   kind(Occluded):t+1 ~= can
                ->  % n = 693 (weight 805), log-likelihood -302.993, logistic
                    logistic([Distance], [-12.7149, 1.67063], P1),
                    P2 is 1-P1
                ;   kind(Occluded):t+1 ~= cup
                ->  (   lift(Occluder):t+1 ~= Lift2
                    ->  (   seen(Occluded):t
                        ->  % n = 49, log-likelihood -6.09022, logistic
                            logistic([Distance, Lift2], [-21.6714, -151.654, 0.923366], P1),
                            P2 is 1-P1
                        ;   % n = 887 (weight 959), log-likelihood -372.813, logistic
                            logistic([Distance, Lift2], [-10.255, -42.7321, 3.08885], P1),
                            P2 is 1-P1
                        )
                    ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                        logistic([Distance], [-9.22649, 2.76553], P1),
                        P2 is 1-P1
                    )
                ;   kind(Occluded):t+1 ~= mug
                ->  (   seen(Occluded):t
                    ->  % n = 59, log-likelihood -7.33852, logistic
                        logistic([Distance], [-36.2589, 2.42747], P1),
                        P2 is 1-P1
                    ;   (   lift(Occluder):t+1 ~= Lift4
                        ->  % n = 1163 (weight 1267), log-likelihood -662.705, logistic
                            logistic([Distance, Lift4], [-9.57738, -27.8547, 2.1184], P1),
                            P2 is 1-P1
                        ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                            logistic([Distance], [-8.86673, 2.0126], P1),
                            P2 is 1-P1
                        )
                    )
                ;   kind(Occluded):t+1 ~= skin
                ->  % n = 0, too few groundings for a model of its own: the parent's model, logistic
                    logistic([Distance], [-11.522, 1.44715], P1),
                    P2 is 1-P1
                ;   \+ kind(Occluded):t+1 ~= _
                ->  % n = 0, too few groundings for a model of its own: the parent's model, logistic
                    logistic([Distance], [-11.522, 1.44715], P1),
                    P2 is 1-P1
                )
            ;   \+ kind(Occluder):t+1 ~= _
            ->  % n = 0, too few groundings for a model of its own: the parent's model, logistic
                logistic([Distance], [-13.8422, 0.738241], P1),
                P2 is 1-P1
            )
        )
    ;   % n = 0, too few groundings for a model of its own: the parent's model, finite
        P1 = 0.18012,
        P2 = 0.81988
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

% released(Held):t+1: 3 clauses, 2953 groundings, training log-likelihood -120.556 (mean -0.0408248 per grounding), 6 parameters.
released(Held):t+1 ~ finite([P1:true, P2:false]) :=
    carried(Held):t+1,
    (   height(Held):t+1 ~= Height
    ->  (   highest(Held):t+1 ~= Highest
        ->  % n = 2953, log-likelihood -120.556, logistic
            logistic([Height, Highest], [-78.022, 36.9771, -5.53863], P1),
            P2 is 1-P1
        ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
            logistic([Height], [-60.6167, -1.12395], P1),
            P2 is 1-P1
        )
    ;   % n = 0, too few groundings for a model of its own: the parent's model, finite
        P1 = 0.0247039,
        P2 = 0.9752961
    ).

:- include('too/too_motion.pl').
