/*  too_learned.pl -- the theory of occlusion with rules learned from experience.

    Written by `anchoring learn-theory`: a tree learned (ddc learn) from
    data_truth.pl: 55832 groundings of occluder(A, O):t+1,
    71 clauses, training log-likelihood -14658.7;
    and one for released(A):t+1 from 1654 frames a hand held an object
    (3 clauses, training log-likelihood -31.628);
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
obs_var(2.625e-06).  % the measurement noise of a perceived position (m², per axis); 80,927 samples
motion_var(3.13e-05).  % how far a perceived object moves in a frame (m², per axis); 95,157 samples
reappear_var(0.002333).  % where a hidden object is seen again, around its belief (m²); 465 samples
lost_var(0.0662).  % the same for an object lost while the camera saw nothing (m²); 6,422 samples
follow_keep(0.8296).  % the fraction of its offset from its occluder a hidden object keeps; 11,318 samples
follow_var(2.596e-05).  % the jitter of that offset per frame (m²); 11,318 samples
coast_keep(0.966).  % the fraction of its velocity a hidden object under nothing keeps; 23,357 samples
wander_var(9.458e-07).  % how far such an object may move besides (m²); 23,357 samples
grip_reach(0.04778).  % how far (table plane) a hand's grip may be from what it takes (m); 38 samples
grip_height(0.1249).  % how far above it (m); 38 samples
occluder_rise(0).  % how far below its centre (m); 38 samples
grip_drop(0.01763).  % how far what a hand holds is below its grip (m); 1,654 samples
grip_rise(0.001853).  % how far a hand's grip rises in a frame when it lifts (m); 467 samples

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
hides(ball, 5.384e-05).  % 18,573
hides(box, 0.1951).  % 35,171
hides(can, 0.000106).  % 9,434
hides(cup, 0.06811).  % 18,381
hides(mug, 0.046).  % 23,802
hides(skin, 0.4804).  % 3,928
hidden_share(ball, 0.17).  % 23,907
hidden_share(box, 7.454e-05).  % 13,414
hidden_share(can, 0.1119).  % 18,875
hidden_share(cup, 0.1297).  % 18,619
hidden_share(mug, 0.1527).  % 16,410
hidden_share(skin, 5.535e-05).  % 18,064
carries(skin, 0.9962).  % 1,038
carrier(skin).
can_occlude(O) := category(O, C), hides(C, P), P >= 0.01, \+ is_carrier(O).
is_carrier(O) := category(O, C), carrier(C).
hand_known := object(O), is_carrier(O).
can_be_occluded(A) := category(A, C), hidden_share(C, P), P >= 0.01.

:- include('too/too_learned_glue.pl').
% The onset reach (m): 90% of the 67 onsets in the data were within 0.04254 m; times 2.0.
onset_reach(0.0851).

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

% occluder(Occluded, Occluder):t+1: 71 clauses, 55832 groundings, training log-likelihood -14658.7 (mean -0.09823 per grounding), 115 parameters.
occluder(Occluded, Occluder):t+1 ~ finite([P1:true, P2:false]) :=
    pair(Occluded, Occluder):t+1,
    (   distance(Occluded, Occluder):t+1 ~= Distance
    ->  (   kind(Occluder):t+1 ~= ball
        ->  % n = 7189 (weight 24705), log-likelihood -0.999939, finite
            P1 = 4.04744e-5,
            P2 = 0.9999595256
        ;   kind(Occluder):t+1 ~= box
        ->  (   kind(Occluded):t+1 ~= ball
            ->  (   occluded_by(Occluded, Occluder):t
                ->  % n = 209 (weight 697), log-likelihood -43.7483, finite
                    P1 = 0.9871245,
                    P2 = 0.0128755
                ;   (   rise(Occluded, Occluder):t+1 ~= Rise
                    ->  (   Rise < 0.0
                        ->  % n = 5 (weight 25), log-likelihood -0.943508, finite
                            P1 = 0.037037,
                            P2 = 0.962963
                        ;   Rise < 0.1
                        ->  % n = 3007 (weight 8691), log-likelihood -1355.07, logistic
                            logistic([Distance], [-19.3083, 0.669531], P1),
                            P2 is 1-P1
                        ;   % n = 539 (weight 707), log-likelihood -38.8448, logistic
                            logistic([Distance], [-15.1723, -1.38543], P1),
                            P2 is 1-P1
                        )
                    ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                        logistic([Distance], [-19.3207, 0.588716], P1),
                        P2 is 1-P1
                    )
                )
            ;   kind(Occluded):t+1 ~= box
            ->  % n = 1485 (weight 4509), log-likelihood -0.999667, finite
                P1 = 0.00022168,
                P2 = 0.99977832
            ;   kind(Occluded):t+1 ~= can
            ->  (   occluded_by(Occluded, Occluder):t
                ->  % n = 371 (weight 1299), log-likelihood -48.7512, finite
                    P1 = 0.99308224,
                    P2 = 0.00691776
                ;   (   rise(Occluded, Occluder):t+1 ~= Rise4
                    ->  (   Rise4 < 0.0
                        ->  % n = 332 (weight 640), log-likelihood -7.32236, logistic
                            logistic([Distance], [-49.6739, 5.63711], P1),
                            P2 is 1-P1
                        ;   Rise4 < 0.1
                        ->  (   lost_anywhere(Occluded):t
                            ->  % n = 157 (weight 549), log-likelihood -7.61132, finite
                                P1 = 0.00362976,
                                P2 = 0.99637024
                            ;   % n = 2030 (weight 4970), log-likelihood -1310.18, logistic
                                logistic([Distance], [-18.6848, 1.64375], P1),
                                P2 is 1-P1
                            )
                        ;   % n = 401 (weight 521), log-likelihood -81.5868, finite
                            P1 = 0.0382409,
                            P2 = 0.9617591
                        )
                    ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                        logistic([Distance], [-19.8862, 1.56349], P1),
                        P2 is 1-P1
                    )
                )
            ;   kind(Occluded):t+1 ~= cup
            ->  (   occluded_by(Occluded, Occluder):t
                ->  % n = 747 (weight 2375), log-likelihood -110.687, finite
                    P1 = 0.99158603,
                    P2 = 0.00841397
                ;   (   rise(Occluded, Occluder):t+1 ~= Rise8
                    ->  (   Rise8 < 0.0
                        ->  % n = 221 (weight 737), log-likelihood -6.98083, logistic
                            logistic([Distance], [-113.078, 2.67841], P1),
                            P2 is 1-P1
                        ;   Rise8 < 0.1
                        ->  (   lost_anywhere(Occluded):t
                            ->  % n = 132 (weight 460), log-likelihood -2.50322, logistic
                                logistic([Distance], [-46.3508, 1.73695], P1),
                                P2 is 1-P1
                            ;   (   seen(Occluded):t
                                ->  % n = 72, log-likelihood -4.51614, logistic
                                    logistic([Distance], [-39.3964, 2.96015], P1),
                                    P2 is 1-P1
                                ;   % n = 3890 (weight 7050), log-likelihood -4364.08, logistic
                                    logistic([Distance], [-3.23924, 0.0408077], P1),
                                    P2 is 1-P1
                                )
                            )
                        ;   % n = 576 (weight 708), log-likelihood -97.1012, logistic
                            logistic([Distance], [-6.83138, -1.95177], P1),
                            P2 is 1-P1
                        )
                    ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                        logistic([Distance], [-3.33626, -0.269453], P1),
                        P2 is 1-P1
                    )
                )
            ;   kind(Occluded):t+1 ~= mug
            ->  (   occluded_by(Occluded, Occluder):t
                ->  % n = 781 (weight 2489), log-likelihood -101.739, finite
                    P1 = 0.99277399,
                    P2 = 0.00722601
                ;   (   rise(Occluded, Occluder):t+1 ~= Rise12
                    ->  (   Rise12 < 0.0
                        ->  % n = 203 (weight 551), log-likelihood -15.7488, logistic
                            logistic([Distance], [-68.0496, 5.28095], P1),
                            P2 is 1-P1
                        ;   Rise12 < 0.1
                        ->  (   lost_anywhere(Occluded):t
                            ->  % n = 28 (weight 120), log-likelihood -2.15486, logistic
                                logistic([Distance], [-83.3298, 1.97405], P1),
                                P2 is 1-P1
                            ;   % n = 4027 (weight 7535), log-likelihood -3015.43, logistic
                                logistic([Distance], [-16.4873, 1.54461], P1),
                                P2 is 1-P1
                            )
                        ;   % n = 717 (weight 877), log-likelihood -83.3005, logistic
                            logistic([Distance], [-29.0838, 0.431477], P1),
                            P2 is 1-P1
                        )
                    ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                        logistic([Distance], [-17.3116, 1.45347], P1),
                        P2 is 1-P1
                    )
                )
            ;   kind(Occluded):t+1 ~= skin
            ->  % n = 1574 (weight 4650), log-likelihood -0.999678, finite
                P1 = 0.000214961,
                P2 = 0.999785039
            ;   \+ kind(Occluded):t+1 ~= _
            ->  % n = 0, too few groundings for a model of its own: the parent's model, logistic
                logistic([Distance], [-15.9721, 1.32827], P1),
                P2 is 1-P1
            )
        ;   kind(Occluder):t+1 ~= can
        ->  % n = 3096 (weight 12088), log-likelihood -0.999876, finite
            P1 = 8.2713e-5,
            P2 = 0.999917287
        ;   kind(Occluder):t+1 ~= cup
        ->  (   kind(Occluded):t+1 ~= ball
            ->  (   occluded_by(Occluded, Occluder):t
                ->  (   lift(Occluder):t+1 ~= Lift
                    ->  % n = 417 (weight 1197), log-likelihood -20.2105, logistic
                        logistic([Distance, Lift], [236.048, -149.024, 5.7006], P1),
                        P2 is 1-P1
                    ;   % n = 0, too few groundings for a model of its own: the parent's model, finite
                        P1 = 0.9891576,
                        P2 = 0.0108424
                    )
                ;   (   lost_anywhere(Occluded):t
                    ->  % n = 47 (weight 223), log-likelihood -6.70511, finite
                        P1 = 0.00888889,
                        P2 = 0.99111111
                    ;   % n = 2864 (weight 6940), log-likelihood -1378.75, logistic
                        logistic([Distance], [-23.6912, 1.98722], P1),
                        P2 is 1-P1
                    )
                )
            ;   kind(Occluded):t+1 ~= box
            ->  % n = 620 (weight 2308), log-likelihood -0.999351, finite
                P1 = 0.0004329,
                P2 = 0.9995671
            ;   kind(Occluded):t+1 ~= can
            ->  % n = 1144 (weight 3888), log-likelihood -0.999614, finite
                P1 = 0.000257069,
                P2 = 0.999742931
            ;   kind(Occluded):t+1 ~= cup
            ->  (   occluded_by(Occluded, Occluder):t
                ->  % n = 10 (weight 38), log-likelihood -4.89358, finite
                    P1 = 0.95,
                    P2 = 0.05
                ;   % n = 817 (weight 2521), log-likelihood -185.783, logistic
                    logistic([Distance], [-16.8004, -1.41677], P1),
                    P2 is 1-P1
                )
            ;   kind(Occluded):t+1 ~= mug
            ->  (   occluded_by(Occluded, Occluder):t
                ->  % n = 7 (weight 15), log-likelihood -3.89235, finite
                    P1 = 0.882353,
                    P2 = 0.117647
                ;   % n = 1014 (weight 3338), log-likelihood -55.3073, logistic
                    logistic([Distance], [-23.5642, -1.84553], P1),
                    P2 is 1-P1
                )
            ;   kind(Occluded):t+1 ~= skin
            ->  % n = 1034 (weight 3766), log-likelihood -0.999602, finite
                P1 = 0.000265393,
                P2 = 0.999734607
            ;   \+ kind(Occluded):t+1 ~= _
            ->  % n = 0, too few groundings for a model of its own: the parent's model, logistic
                logistic([Distance], [-31.7287, 1.70907], P1),
                P2 is 1-P1
            )
        ;   kind(Occluder):t+1 ~= mug
        ->  (   kind(Occluded):t+1 ~= ball
            ->  (   occluded_by(Occluded, Occluder):t
                ->  (   lift(Occluder):t+1 ~= Lift2
                    ->  (   rise(Occluded, Occluder):t+1 ~= Rise16
                        ->  (   Rise16 < 0.0
                            ->  % n = 0, too few groundings for a model of its own: the parent's model, logistic
                                logistic([Distance, Lift2], [729.887, -274.582, 4.0218], P1),
                                P2 is 1-P1
                            ;   Rise16 < 0.1
                            ->  % n = 316 (weight 1080), log-likelihood -19.637, logistic
                                logistic([Distance, Lift2], [181.632, -1112.86, 8.9591], P1),
                                P2 is 1-P1
                            ;   % n = 8 (weight 12), log-likelihood -5.49251, finite
                                P1 = 0.785714,
                                P2 = 0.214286
                            )
                        ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                            logistic([Distance, Lift2], [729.887, -274.582, 4.0218], P1),
                            P2 is 1-P1
                        )
                    ;   % n = 0, too few groundings for a model of its own: the parent's model, finite
                        P1 = 0.9844607,
                        P2 = 0.0155393
                    )
                ;   % n = 3352 (weight 8556), log-likelihood -1028.86, logistic
                    logistic([Distance], [-29.6522, 1.84587], P1),
                    P2 is 1-P1
                )
            ;   kind(Occluded):t+1 ~= box
            ->  % n = 1026 (weight 3194), log-likelihood -0.999531, finite
                P1 = 0.000312891,
                P2 = 0.999687109
            ;   kind(Occluded):t+1 ~= can
            ->  % n = 1847 (weight 6027), log-likelihood -0.999751, finite
                P1 = 0.000165865,
                P2 = 0.999834135
            ;   kind(Occluded):t+1 ~= cup
            ->  % n = 1549 (weight 4985), log-likelihood -0.999699, finite
                P1 = 0.000200521,
                P2 = 0.999799479
            ;   kind(Occluded):t+1 ~= mug
            ->  % n = 1018 (weight 3262), log-likelihood -0.99954, finite
                P1 = 0.000306373,
                P2 = 0.999693627
            ;   kind(Occluded):t+1 ~= skin
            ->  % n = 1073 (weight 3861), log-likelihood -0.999612, finite
                P1 = 0.000258866,
                P2 = 0.999741134
            ;   \+ kind(Occluded):t+1 ~= _
            ->  % n = 0, too few groundings for a model of its own: the parent's model, logistic
                logistic([Distance], [-48.8951, 1.23852], P1),
                P2 is 1-P1
            )
        ;   kind(Occluder):t+1 ~= skin
        ->  (   kind(Occluded):t+1 ~= ball
            ->  (   occluded_by(Occluded, Occluder):t
                ->  (   lift(Occluder):t+1 ~= Lift4
                    ->  % n = 815 (weight 1059), log-likelihood -13.0594, logistic
                        logistic([Distance, Lift4], [3.8068, -147.114, 7.90667], P1),
                        P2 is 1-P1
                    ;   % n = 0, too few groundings for a model of its own: the parent's model, finite
                        P1 = 0.99057493,
                        P2 = 0.00942507
                    )
                ;   (   lift(Occluder):t+1 ~= Lift6
                    ->  % n = 1619 (weight 1695), log-likelihood -800.633, logistic
                        logistic([Distance, Lift6], [-8.45422, -21.1508, 2.34853], P1),
                        P2 is 1-P1
                    ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                        logistic([Distance], [-8.16117, 2.29772], P1),
                        P2 is 1-P1
                    )
                )
            ;   kind(Occluded):t+1 ~= box
            ->  % n = 178 (weight 214), log-likelihood -0.993041, finite
                P1 = 0.00462963,
                P2 = 0.99537037
            ;   kind(Occluded):t+1 ~= can
            ->  (   lost_anywhere(Occluded):t
                ->  % n = 60 (weight 68), log-likelihood -0.978434, finite
                    P1 = 0.0142857,
                    P2 = 0.9857143
                ;   (   lift(Occluder):t+1 ~= Lift8
                    ->  (   rise(Occluded, Occluder):t+1 ~= Rise20
                        ->  (   Rise20 < 0.0
                            ->  % n = 33 (weight 37), log-likelihood -0.961093, finite
                                P1 = 0.025641,
                                P2 = 0.974359
                            ;   Rise20 < 0.1
                            ->  % n = 402 (weight 450), log-likelihood -142.721, logistic
                                logistic([Distance, Lift8], [-9.86668, -26.6591, 3.08227], P1),
                                P2 is 1-P1
                            ;   (   occluded_by(Occluded, Occluder):t
                                ->  % n = 426 (weight 638), log-likelihood -3.82383, logistic
                                    logistic([Distance, Lift8], [-106.416, -293.763, 9.3665], P1),
                                    P2 is 1-P1
                                ;   % n = 775 (weight 811), log-likelihood -273.681, logistic
                                    logistic([Distance, Lift8], [-12.5796, -68.0461, 3.75406], P1),
                                    P2 is 1-P1
                                )
                            )
                        ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                            logistic([Distance, Lift8], [-12.7428, -57.5016, 3.69338], P1),
                            P2 is 1-P1
                        )
                    ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                        logistic([Distance], [-11.4228, 3.34938], P1),
                        P2 is 1-P1
                    )
                )
            ;   kind(Occluded):t+1 ~= cup
            ->  % n = 748 (weight 948), log-likelihood -0.99842, finite
                P1 = 0.00105263,
                P2 = 0.99894737
            ;   kind(Occluded):t+1 ~= mug
            ->  % n = 824 (weight 1072), log-likelihood -0.998603, finite
                P1 = 0.000931099,
                P2 = 0.999068901
            ;   kind(Occluded):t+1 ~= skin
            ->  % n = 0, too few groundings for a model of its own: the parent's model, logistic
                logistic([Distance], [-13.9942, 2.45212], P1),
                P2 is 1-P1
            ;   \+ kind(Occluded):t+1 ~= _
            ->  % n = 0, too few groundings for a model of its own: the parent's model, logistic
                logistic([Distance], [-13.9942, 2.45212], P1),
                P2 is 1-P1
            )
        ;   \+ kind(Occluder):t+1 ~= _
        ->  % n = 0, too few groundings for a model of its own: the parent's model, logistic
            logistic([Distance], [-19.8175, 1.16692], P1),
            P2 is 1-P1
        )
    ;   % n = 0, too few groundings for a model of its own: the parent's model, finite
        P1 = 0.150586,
        P2 = 0.849414
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

% released(Held):t+1: 3 clauses, 1654 groundings, training log-likelihood -31.628 (mean -0.0191221 per grounding), 6 parameters.
released(Held):t+1 ~ finite([P1:true, P2:false]) :=
    carried(Held):t+1,
    (   height(Held):t+1 ~= Height
    ->  (   highest(Held):t+1 ~= Highest
        ->  % n = 1654, log-likelihood -31.628, logistic
            logistic([Height, Highest], [-172.327, 34.7062, -4.39297], P1),
            P2 is 1-P1
        ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
            logistic([Height], [-109.242, -0.713546], P1),
            P2 is 1-P1
        )
    ;   % n = 0, too few groundings for a model of its own: the parent's model, finite
        P1 = 0.0247585,
        P2 = 0.9752415
    ).

:- include('too/too_motion.pl').
