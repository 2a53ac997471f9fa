/*  too_learned.pl -- the theory of occlusion with rules learned from experience.

    Written by `anchoring learn-theory`: a tree learned (ddc learn) from
    data_truth.pl: 19875 groundings of occluder(A, O):t+1,
    112 clauses, training log-likelihood -4504.85;
    and one for released(A):t+1 from 2486 frames a hand held an object
    (3 clauses, training log-likelihood -74.478);
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
obs_var(5.523e-06).  % the measurement noise of a perceived position (m², per axis); 105,844 samples
motion_var(2.961e-05).  % how far a perceived object moves in a frame (m², per axis); 122,418 samples
reappear_var(0.002192).  % where a hidden object is seen again, around its belief (m²); 1,267 samples
lost_var(0.07154).  % the same for an object lost while the camera saw nothing (m²); 8,187 samples
follow_keep(0.9262).  % the fraction of its offset from its occluder a hidden object keeps; 15,037 samples
follow_var(1.441e-05).  % the jitter of that offset per frame (m²); 15,037 samples
coast_keep(0.8864).  % the fraction of its velocity a hidden object under nothing keeps; 237 samples
wander_var(0.0001671).  % how far such an object may move besides (m²); 237 samples
rest_var(6.69e-06).  % how far one that stood still as it vanished may move (m²); 928 samples
height_var(1e-08).  % how far a hidden object's height may move (m² a frame); 1,170 samples
grip_reach(0.1482).  % how far (table plane) a hand's grip may be from what it takes (m); 52 samples
grip_height(0.1178).  % how far above its top (m); 52 samples
occluder_rise(0.009905).  % how far below its centre (m); 52 samples
grip_drop(0.02111).  % how far what a hand holds is below its grip (m); 2,484 samples
grip_rise(0.001216).  % how far a hand's grip rises in a frame when it lifts (m); 717 samples
moving_speed(0.004).  % (m a frame) what the fits above call moving as it vanished (wander_var) and still (rest_var)
% The height of each kind (m): the median of its perceived heights; a grip's height
% over an object is measured from its top (too/too_motion.pl).
kind_height(ball, 0.059).  % 1,213 samples
kind_height(bottle, 0.2128).  % 729 samples
kind_height(bowl, 0.0868).  % 701 samples
kind_height(box, 0.134).  % 1,761 samples
kind_height(can, 0.1232).  % 547 samples
kind_height(cup, 0.1037).  % 1,565 samples
kind_height(mug, 0.1026).  % 1,671 samples

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
hides(ball, 0.0007703).  % 15,576
hides(bottle, 8.407e-05).  % 11,893
hides(bowl, 0.1579).  % 12,145
hides(box, 0.2196).  % 27,227
hides(can, 0.0001241).  % 8,057
hides(cup, 0.1005).  % 20,897
hides(mug, 0.1132).  % 21,959
hides(skin, 0.4984).  % 4,689
hidden_share(ball, 0.2288).  % 45,934
hidden_share(bottle, 0.1527).  % 2,152
hidden_share(bowl, 0.05359).  % 2,965
hidden_share(box, 0.02286).  % 9,361
hidden_share(can, 0.1396).  % 4,476
hidden_share(cup, 0.1611).  % 13,031
hidden_share(mug, 0.06839).  % 13,085
hidden_share(skin, 3.181e-05).  % 31,439
carries(bowl, 0.5).  % 2
carries(box, 0.25).  % 2
carries(skin, 0.9983).  % 1,170
carrier(skin).
can_occlude(O) := category(O, C), hides(C, P), P >= 0.01, \+ is_carrier(O).
is_carrier(O) := category(O, C), carrier(C).
hand_known := object(O), is_carrier(O).
can_be_occluded(A) := category(A, C), hidden_share(C, P), P >= 0.01.

:- include('too/too_learned_glue.pl').
% The onset reach (m): 90% of the 61 onsets in the data (6 far out left out) were within 0.07701 m; times 2.0.
onset_reach(0.154).
% The reach of the kinds with onsets enough for one of their own.
onset_reach(box, 0.0881).  % 35 onsets, (5 far out left out) 90% within 0.04405 m
onset_reach(cup, 0.0632).  % 10 onsets, (2 far out left out) 90% within 0.03162 m
onset_reach(mug, 0.0549).  % 10 onsets, (1 far out left out) 90% within 0.02745 m

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

% occluder(Occluded, Occluder):t+1: 112 clauses, 19875 groundings, training log-likelihood -4504.85 (mean -0.116012 per grounding), 160 parameters.
occluder(Occluded, Occluder):t+1 ~ finite([P1:true, P2:false]) :=
    pair(Occluded, Occluder):t+1,
    (   distance(Occluded, Occluder):t+1 ~= Distance
    ->  (   kind(Occluder):t+1 ~= ball
        ->  (   moved(Occluder):t+1 ~= Moved
            ->  (   Moved < 0.004
                ->  % n = 452 (weight 2124), log-likelihood -0.999294, finite
                    P1 = 0.000470367,
                    P2 = 0.999529633
                ;   % n = 412 (weight 484), log-likelihood -31.2526, logistic
                    logistic([Distance], [-23.2868, -0.487393], P1),
                    P2 is 1-P1
                )
            ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                logistic([Distance], [-28.7424, -2.24696], P1),
                P2 is 1-P1
            )
        ;   kind(Occluder):t+1 ~= bottle
        ->  % n = 439 (weight 1687), log-likelihood -0.999112, finite
            P1 = 0.000592066,
            P2 = 0.999407934
        ;   kind(Occluder):t+1 ~= bowl
        ->  (   kind(Occluded):t+1 ~= ball
            ->  (   occluded_by(Occluded, Occluder):t
                ->  (   rise(Occluded, Occluder):t+1 ~= Rise
                    ->  (   Rise < 0.0
                        ->  % n = 51 (weight 167), log-likelihood -0.991101, finite
                            P1 = 0.99408284,
                            P2 = 0.00591716
                        ;   Rise < 0.1
                        ->  % n = 517 (weight 1705), log-likelihood -0.999121, finite
                            P1 = 0.999414177,
                            P2 = 0.000585823
                        ;   % n = 29 (weight 45), log-likelihood -19.4852, finite
                            P1 = 0.829787,
                            P2 = 0.170213
                        )
                    ;   % n = 0, too few groundings for a model of its own: the parent's model, finite
                        P1 = 0.99583116,
                        P2 = 0.00416884
                    )
                ;   (   rise(Occluded, Occluder):t+1 ~= Rise4
                    ->  (   Rise4 < 0.0
                        ->  % n = 132 (weight 180), log-likelihood -1.75438, logistic
                            logistic([Distance], [-144.301, 10.5719], P1),
                            P2 is 1-P1
                        ;   Rise4 < 0.1
                        ->  (   seen(Occluder):t
                            ->  (   moved(Occluder):t+1 ~= Moved3
                                ->  (   Moved3 < 0.004
                                    ->  % n = 812 (weight 1160), log-likelihood -769.427, finite
                                        P1 = 0.621343,
                                        P2 = 0.378657
                                    ;   % n = 344 (weight 388), log-likelihood -243.593, logistic
                                        logistic([Distance], [-16.0838, 0.94355], P1),
                                        P2 is 1-P1
                                    )
                                ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                                    logistic([Distance], [-8.66113, 0.71555], P1),
                                    P2 is 1-P1
                                )
                            ;   % n = 31 (weight 47), log-likelihood -13.7576, finite
                                P1 = 0.102041,
                                P2 = 0.897959
                            )
                        ;   (   moved(Occluder):t+1 ~= Moved6
                            ->  (   Moved6 < 0.004
                                ->  % n = 18, log-likelihood -0.923279, finite
                                    P1 = 0.95,
                                    P2 = 0.05
                                ;   % n = 31, log-likelihood -21.0841, finite
                                    P1 = 0.575758,
                                    P2 = 0.424242
                                )
                            ;   % n = 0, too few groundings for a model of its own: the parent's model, finite
                                P1 = 0.72549,
                                P2 = 0.27451
                            )
                        )
                    ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                        logistic([Distance], [-12.8453, 0.936269], P1),
                        P2 is 1-P1
                    )
                )
            ;   kind(Occluded):t+1 ~= bottle
            ->  % n = 22 (weight 30), log-likelihood -0.952461, finite
                P1 = 0.03125,
                P2 = 0.96875
            ;   kind(Occluded):t+1 ~= bowl
            ->  % n = 1 (weight 5), too few groundings for a model of its own: the parent's model, log-likelihood -5.69665, logistic
                logistic([Distance], [-36.1291, 2.00012], P1),
                P2 is 1-P1
            ;   kind(Occluded):t+1 ~= box
            ->  % n = 59 (weight 183), log-likelihood -0.991872, finite
                P1 = 0.00540541,
                P2 = 0.99459459
            ;   kind(Occluded):t+1 ~= can
            ->  % n = 30 (weight 38), log-likelihood -0.962077, finite
                P1 = 0.025,
                P2 = 0.975
            ;   kind(Occluded):t+1 ~= cup
            ->  % n = 206 (weight 422), log-likelihood -0.996459, finite
                P1 = 0.00235849,
                P2 = 0.99764151
            ;   kind(Occluded):t+1 ~= mug
            ->  % n = 174 (weight 598), log-likelihood -0.997498, finite
                P1 = 0.00166667,
                P2 = 0.99833333
            ;   kind(Occluded):t+1 ~= skin
            ->  % n = 7 (weight 19), log-likelihood -0.927013, finite
                P1 = 0.047619,
                P2 = 0.952381
            ;   \+ kind(Occluded):t+1 ~= _
            ->  % n = 0, too few groundings for a model of its own: the parent's model, logistic
                logistic([Distance], [-36.1291, 2.00012], P1),
                P2 is 1-P1
            )
        ;   kind(Occluder):t+1 ~= box
        ->  (   kind(Occluded):t+1 ~= ball
            ->  (   occluded_by(Occluded, Occluder):t
                ->  (   moved(Occluder):t+1 ~= Moved9
                    ->  (   Moved9 < 0.004
                        ->  % n = 515 (weight 2575), log-likelihood -0.999418, finite
                            P1 = 0.999611952,
                            P2 = 0.000388048
                        ;   (   lift(Occluder):t+1 ~= Lift
                            ->  % n = 743 (weight 1011), log-likelihood -64.1959, logistic
                                logistic([Distance, Lift], [354.507, -64.117, 2.68566], P1),
                                P2 is 1-P1
                            ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                                logistic([Distance], [429.552, 2.17211], P1),
                                P2 is 1-P1
                            )
                        )
                    ;   % n = 0, too few groundings for a model of its own: the parent's model, finite
                        P1 = 0.99386845,
                        P2 = 0.00613155
                    )
                ;   (   lost_anywhere(Occluded):t
                    ->  (   seen(Occluder):t
                        ->  % n = 38 (weight 190), log-likelihood -0.992169, finite
                            P1 = 0.00520833,
                            P2 = 0.99479167
                        ;   % n = 13, log-likelihood -8.66806, finite
                            P1 = 0.4,
                            P2 = 0.6
                        )
                    ;   (   rise(Occluded, Occluder):t+1 ~= Rise8
                        ->  (   Rise8 < 0.0
                            ->  % n = 0, too few groundings for a model of its own: the parent's model, logistic
                                logistic([Distance], [-23.7261, 1.59914], P1),
                                P2 is 1-P1
                            ;   Rise8 < 0.1
                            ->  (   moved(Occluder):t+1 ~= Moved12
                                ->  (   Moved12 < 0.004
                                    ->  % n = 1882 (weight 2298), log-likelihood -1179.27, logistic
                                        logistic([Distance], [-21.4609, 1.73224], P1),
                                        P2 is 1-P1
                                    ;   % n = 523 (weight 547), log-likelihood -354.308, logistic
                                        logistic([Distance], [-17.2971, 1.02005], P1),
                                        P2 is 1-P1
                                    )
                                ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                                    logistic([Distance], [-22.1523, 1.62458], P1),
                                    P2 is 1-P1
                                )
                            ;   % n = 78 (weight 86), log-likelihood -35.4303, logistic
                                logistic([Distance], [-47.9994, 0.203861], P1),
                                P2 is 1-P1
                            )
                        ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                            logistic([Distance], [-23.7261, 1.59914], P1),
                            P2 is 1-P1
                        )
                    )
                )
            ;   kind(Occluded):t+1 ~= bottle
            ->  % n = 15 (weight 23), log-likelihood -0.938906, finite
                P1 = 0.04,
                P2 = 0.96
            ;   kind(Occluded):t+1 ~= bowl
            ->  % n = 27 (weight 63), log-likelihood -0.976764, finite
                P1 = 0.0153846,
                P2 = 0.9846154
            ;   kind(Occluded):t+1 ~= box
            ->  % n = 196 (weight 696), log-likelihood -0.99785, finite
                P1 = 0.00143266,
                P2 = 0.99856734
            ;   kind(Occluded):t+1 ~= can
            ->  (   moved(Occluder):t+1 ~= Moved15
                ->  (   Moved15 < 0.004
                    ->  % n = 507 (weight 887), log-likelihood -0.998312, finite
                        P1 = 0.99887514,
                        P2 = 0.00112486
                    ;   (   occluded_by(Occluded, Occluder):t
                        ->  % n = 55 (weight 79), log-likelihood -12.8734, finite
                            P1 = 0.9506173,
                            P2 = 0.0493827
                        ;   % n = 102 (weight 114), log-likelihood -37.0748, logistic
                            logistic([Distance], [-86.6373, 3.38713], P1),
                            P2 is 1-P1
                        )
                    )
                ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                    logistic([Distance], [-106.827, 5.24125], P1),
                    P2 is 1-P1
                )
            ;   kind(Occluded):t+1 ~= cup
            ->  (   rise(Occluded, Occluder):t+1 ~= Rise12
                ->  (   Rise12 < 0.0
                    ->  % n = 0, too few groundings for a model of its own: the parent's model, logistic
                        logistic([Distance], [-75.1297, 4.59196], P1),
                        P2 is 1-P1
                    ;   Rise12 < 0.1
                    ->  (   lost_anywhere(Occluded):t
                        ->  % n = 8 (weight 32), log-likelihood -0.566375, logistic
                            logistic([Distance], [-1656.49, 74.8099], P1),
                            P2 is 1-P1
                        ;   (   moved(Occluder):t+1 ~= Moved18
                            ->  (   Moved18 < 0.004
                                ->  % n = 1393 (weight 2517), log-likelihood -339.179, logistic
                                    logistic([Distance], [-95.6384, 5.90576], P1),
                                    P2 is 1-P1
                                ;   (   occluded_by(Occluded, Occluder):t
                                    ->  % n = 159 (weight 191), log-likelihood -15.5665, finite
                                        P1 = 0.9792746,
                                        P2 = 0.0207254
                                    ;   % n = 95 (weight 107), log-likelihood -73.1122, finite
                                        P1 = 0.431193,
                                        P2 = 0.568807
                                    )
                                )
                            ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                                logistic([Distance], [-73.2977, 4.78126], P1),
                                P2 is 1-P1
                            )
                        )
                    ;   % n = 24 (weight 28), log-likelihood -9.62223, finite
                        P1 = 0.133333,
                        P2 = 0.866667
                    )
                ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                    logistic([Distance], [-75.1297, 4.59196], P1),
                    P2 is 1-P1
                )
            ;   kind(Occluded):t+1 ~= mug
            ->  (   occluded_by(Occluded, Occluder):t
                ->  % n = 95 (weight 335), log-likelihood -7.11504, finite
                    P1 = 0.99406528,
                    P2 = 0.00593472
                ;   (   lift(Occluder):t+1 ~= Lift2
                    ->  % n = 256 (weight 640), log-likelihood -222.623, logistic
                        logistic([Distance, Lift2], [-57.2976, -297.838, -0.134059], P1),
                        P2 is 1-P1
                    ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                        logistic([Distance], [-57.8606, -0.100422], P1),
                        P2 is 1-P1
                    )
                )
            ;   kind(Occluded):t+1 ~= skin
            ->  % n = 281 (weight 965), log-likelihood -0.998448, finite
                P1 = 0.00103413,
                P2 = 0.99896587
            ;   \+ kind(Occluded):t+1 ~= _
            ->  % n = 0, too few groundings for a model of its own: the parent's model, logistic
                logistic([Distance], [-58.9301, 2.87007], P1),
                P2 is 1-P1
            )
        ;   kind(Occluder):t+1 ~= can
        ->  % n = 374 (weight 1406), log-likelihood -0.998934, finite
            P1 = 0.000710227,
            P2 = 0.999289773
        ;   kind(Occluder):t+1 ~= cup
        ->  (   kind(Occluded):t+1 ~= ball
            ->  (   seen(Occluder):t
                ->  (   lift(Occluder):t+1 ~= Lift4
                    ->  (   rise(Occluded, Occluder):t+1 ~= Rise16
                        ->  (   Rise16 < 0.0
                            ->  % n = 62 (weight 182), log-likelihood -0.991828, finite
                                P1 = 0.99456522,
                                P2 = 0.00543478
                            ;   Rise16 < 0.1
                            ->  % n = 1813 (weight 3317), log-likelihood -72.7575, logistic
                                logistic([Distance, Lift4], [-214.809, -773.311, 8.17447], P1),
                                P2 is 1-P1
                            ;   (   moved(Occluder):t+1 ~= Moved21
                                ->  (   Moved21 < 0.004
                                    ->  % n = 6 (weight 14), log-likelihood -0.903539, finite
                                        P1 = 0.9375,
                                        P2 = 0.0625
                                    ;   % n = 22, log-likelihood -15.2492, finite
                                        P1 = 0.5,
                                        P2 = 0.5
                                    )
                                ;   % n = 0, too few groundings for a model of its own: the parent's model, finite
                                    P1 = 0.684211,
                                    P2 = 0.315789
                                )
                            )
                        ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                            logistic([Distance, Lift4], [-180.562, -327.611, 6.60674], P1),
                            P2 is 1-P1
                        )
                    ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                        logistic([Distance], [-162.905, 5.88982], P1),
                        P2 is 1-P1
                    )
                ;   % n = 14 (weight 18), log-likelihood -12.3664, finite
                    P1 = 0.45,
                    P2 = 0.55
                )
            ;   kind(Occluded):t+1 ~= bottle
            ->  % n = 0, too few groundings for a model of its own: the parent's model, logistic
                logistic([Distance], [-121.38, 4.35636], P1),
                P2 is 1-P1
            ;   kind(Occluded):t+1 ~= bowl
            ->  % n = 0, too few groundings for a model of its own: the parent's model, logistic
                logistic([Distance], [-121.38, 4.35636], P1),
                P2 is 1-P1
            ;   kind(Occluded):t+1 ~= box
            ->  % n = 32 (weight 132), log-likelihood -0.988769, finite
                P1 = 0.00746269,
                P2 = 0.99253731
            ;   kind(Occluded):t+1 ~= can
            ->  % n = 1, too few groundings for a model of its own: the parent's model, log-likelihood -0.0831746, logistic
                logistic([Distance], [-121.38, 4.35636], P1),
                P2 is 1-P1
            ;   kind(Occluded):t+1 ~= cup
            ->  % n = 7 (weight 27), log-likelihood -0.947466, finite
                P1 = 0.0344828,
                P2 = 0.9655172
            ;   kind(Occluded):t+1 ~= mug
            ->  % n = 29 (weight 73), log-likelihood -0.97988, finite
                P1 = 0.0133333,
                P2 = 0.9866667
            ;   kind(Occluded):t+1 ~= skin
            ->  % n = 287 (weight 931), log-likelihood -0.998392, finite
                P1 = 0.00107181,
                P2 = 0.99892819
            ;   \+ kind(Occluded):t+1 ~= _
            ->  % n = 0, too few groundings for a model of its own: the parent's model, logistic
                logistic([Distance], [-121.38, 4.35636], P1),
                P2 is 1-P1
            )
        ;   kind(Occluder):t+1 ~= mug
        ->  (   kind(Occluded):t+1 ~= ball
            ->  (   lift(Occluder):t+1 ~= Lift6
                ->  (   occluded_by(Occluded, Occluder):t
                    ->  % n = 637 (weight 2473), log-likelihood -14.0731, logistic
                        logistic([Distance, Lift6], [274.967, -993.035, 8.08215], P1),
                        P2 is 1-P1
                    ;   (   moved(Occluder):t+1 ~= Moved24
                        ->  (   Moved24 < 0.004
                            ->  (   seen(Occluder):t
                                ->  % n = 1316 (weight 1348), log-likelihood -85.976, logistic
                                    logistic([Distance, Lift6], [616.21, 580.42, -3.97792], P1),
                                    P2 is 1-P1
                                ;   % n = 7 (weight 11), log-likelihood -7.58018, finite
                                    P1 = 0.538462,
                                    P2 = 0.461538
                                )
                            ;   % n = 149 (weight 153), log-likelihood -62.2485, logistic
                                logistic([Distance, Lift6], [-84.9294, -212.941, 3.35532], P1),
                                P2 is 1-P1
                            )
                        ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                            logistic([Distance, Lift6], [-46.6116, -265.832, 3.63862], P1),
                            P2 is 1-P1
                        )
                    )
                ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                    logistic([Distance], [-73.555, 4.50654], P1),
                    P2 is 1-P1
                )
            ;   kind(Occluded):t+1 ~= bottle
            ->  % n = 0, too few groundings for a model of its own: the parent's model, logistic
                logistic([Distance], [-86.0151, 4.29917], P1),
                P2 is 1-P1
            ;   kind(Occluded):t+1 ~= bowl
            ->  % n = 3 (weight 15), log-likelihood -0.0903584, logistic
                logistic([Distance], [-47.2191, 4.733], P1),
                P2 is 1-P1
            ;   kind(Occluded):t+1 ~= box
            ->  % n = 11 (weight 43), log-likelihood -0.966333, finite
                P1 = 0.0222222,
                P2 = 0.9777778
            ;   kind(Occluded):t+1 ~= can
            ->  % n = 0, too few groundings for a model of its own: the parent's model, logistic
                logistic([Distance], [-86.0151, 4.29917], P1),
                P2 is 1-P1
            ;   kind(Occluded):t+1 ~= cup
            ->  % n = 13, log-likelihood -0.896907, finite
                P1 = 0.0666667,
                P2 = 0.9333333
            ;   kind(Occluded):t+1 ~= mug
            ->  % n = 94 (weight 214), log-likelihood -0.993041, finite
                P1 = 0.00462963,
                P2 = 0.99537037
            ;   kind(Occluded):t+1 ~= skin
            ->  % n = 336 (weight 1132), log-likelihood -0.998677, finite
                P1 = 0.000881834,
                P2 = 0.999118166
            ;   \+ kind(Occluded):t+1 ~= _
            ->  % n = 0, too few groundings for a model of its own: the parent's model, logistic
                logistic([Distance], [-86.0151, 4.29917], P1),
                P2 is 1-P1
            )
        ;   kind(Occluder):t+1 ~= skin
        ->  (   kind(Occluded):t+1 ~= ball
            ->  (   occluded_by(Occluded, Occluder):t
                ->  % n = 321 (weight 413), log-likelihood -7.32547, finite
                    P1 = 0.99518072,
                    P2 = 0.00481928
                ;   % n = 583 (weight 635), log-likelihood -267.337, logistic
                    logistic([Distance], [-35.5707, 2.42714], P1),
                    P2 is 1-P1
                )
            ;   kind(Occluded):t+1 ~= bottle
            ->  (   rise(Occluded, Occluder):t+1 ~= Rise20
                ->  (   Rise20 < 0.0
                    ->  % n = 2, too few groundings for a model of its own: the parent's model, log-likelihood -2.22243, logistic
                        logistic([Distance], [-19.7561, 3.27229], P1),
                        P2 is 1-P1
                    ;   Rise20 < 0.1
                    ->  % n = 169 (weight 209), log-likelihood -15.0925, logistic
                        logistic([Distance], [-124.785, 4.49506], P1),
                        P2 is 1-P1
                    ;   (   occluded_by(Occluded, Occluder):t
                        ->  % n = 134 (weight 194), log-likelihood -0.99233, finite
                            P1 = 0.99489796,
                            P2 = 0.00510204
                        ;   (   moved(Occluder):t+1 ~= Moved27
                            ->  (   Moved27 < 0.004
                                ->  % n = 65, log-likelihood -0.977462, finite
                                    P1 = 0.9850746,
                                    P2 = 0.0149254
                                ;   % n = 101, log-likelihood -38.8008, logistic
                                    logistic([Distance], [36.9167, 0.88795], P1),
                                    P2 is 1-P1
                                )
                            ;   % n = 0, too few groundings for a model of its own: the parent's model, finite
                                P1 = 0.89881,
                                P2 = 0.10119
                            )
                        )
                    )
                ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                    logistic([Distance], [-19.7561, 3.27229], P1),
                    P2 is 1-P1
                )
            ;   kind(Occluded):t+1 ~= bowl
            ->  (   seen(Occluded):t
                ->  % n = 11, log-likelihood -6.47776, finite
                    P1 = 0.307692,
                    P2 = 0.692308
                ;   (   occluded_by(Occluded, Occluder):t
                    ->  (   lift(Occluder):t+1 ~= Lift8
                        ->  % n = 106 (weight 146), log-likelihood -3.50167, logistic
                            logistic([Distance, Lift8], [-44.0569, -136.173, 5.90011], P1),
                            P2 is 1-P1
                        ;   % n = 0, too few groundings for a model of its own: the parent's model, finite
                            P1 = 0.972973,
                            P2 = 0.027027
                        )
                    ;   % n = 124 (weight 128), log-likelihood -46.2652, finite
                        P1 = 0.876923,
                        P2 = 0.123077
                    )
                )
            ;   kind(Occluded):t+1 ~= box
            ->  % n = 309 (weight 397), log-likelihood -101.178, logistic
                logistic([Distance], [-47.2045, 3.73458], P1),
                P2 is 1-P1
            ;   kind(Occluded):t+1 ~= can
            ->  % n = 155 (weight 167), log-likelihood -25.1679, logistic
                logistic([Distance], [-55.5187, 4.38202], P1),
                P2 is 1-P1
            ;   kind(Occluded):t+1 ~= cup
            ->  (   lift(Occluder):t+1 ~= Lift10
                ->  % n = 986 (weight 1142), log-likelihood -101.581, logistic
                    logistic([Distance, Lift10], [-46.8672, -98.743, 6.31458], P1),
                    P2 is 1-P1
                ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                    logistic([Distance], [-39.9517, 5.50089], P1),
                    P2 is 1-P1
                )
            ;   kind(Occluded):t+1 ~= mug
            ->  (   lift(Occluder):t+1 ~= Lift12
                ->  (   seen(Occluded):t
                    ->  % n = 15, log-likelihood -9.56045, finite
                        P1 = 0.647059,
                        P2 = 0.352941
                    ;   % n = 809 (weight 953), log-likelihood -113.994, logistic
                        logistic([Distance, Lift12], [-30.429, -83.7878, 4.67951], P1),
                        P2 is 1-P1
                    )
                ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                    logistic([Distance], [-23.7976, 3.96983], P1),
                    P2 is 1-P1
                )
            ;   kind(Occluded):t+1 ~= skin
            ->  % n = 0, too few groundings for a model of its own: the parent's model, logistic
                logistic([Distance], [-36.0239, 3.81619], P1),
                P2 is 1-P1
            ;   \+ kind(Occluded):t+1 ~= _
            ->  % n = 0, too few groundings for a model of its own: the parent's model, logistic
                logistic([Distance], [-36.0239, 3.81619], P1),
                P2 is 1-P1
            )
        ;   \+ kind(Occluder):t+1 ~= _
        ->  % n = 0, too few groundings for a model of its own: the parent's model, logistic
            logistic([Distance], [-49.5928, 2.87574], P1),
            P2 is 1-P1
        )
    ;   % n = 0, too few groundings for a model of its own: the parent's model, finite
        P1 = 0.618546,
        P2 = 0.381454
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

% released(Held):t+1: 3 clauses, 2486 groundings, training log-likelihood -74.478 (mean -0.029959 per grounding), 6 parameters.
released(Held):t+1 ~ finite([P1:true, P2:false]) :=
    carried(Held):t+1,
    (   height(Held):t+1 ~= Height
    ->  (   highest(Held):t+1 ~= Highest
        ->  % n = 2486, log-likelihood -74.478, logistic
            logistic([Height, Highest], [-103.808, 63.3374, -9.1449], P1),
            P2 is 1-P1
        ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
            logistic([Height], [-48.4773, -1.49431], P1),
            P2 is 1-P1
        )
    ;   % n = 0, too few groundings for a model of its own: the parent's model, finite
        P1 = 0.0249196,
        P2 = 0.9750804
    ).

:- include('too/too_motion.pl').
