/*  too_learned.pl -- the theory of occlusion with rules learned from experience.

    Written by `anchoring learn-theory`: a tree learned (ddc learn) from
    data_truth.pl: 21825 groundings of occluder(A, O):t+1,
    119 clauses, training log-likelihood -4961.2;
    and one for released(A):t+1 from 2442 frames a hand held an object
    (3 clauses, training log-likelihood -73.6101);
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
obs_var(5.105e-06).  % the measurement noise of a perceived position (m², per axis); 105,440 samples
motion_var(2.975e-05).  % how far a perceived object moves in a frame (m², per axis); 122,008 samples
reappear_var(0.002513).  % where a hidden object is seen again, around its belief (m²); 1,292 samples
lost_var(0.07162).  % the same for an object lost while the camera saw nothing (m²); 8,160 samples
follow_keep(0.9396).  % the fraction of its offset from its occluder a hidden object keeps; 14,944 samples
follow_var(1.088e-05).  % the jitter of that offset per frame (m²); 14,944 samples
coast_keep(0.8954).  % the fraction of its velocity a hidden object under nothing keeps; 245 samples
wander_var(0.0001911).  % how far such an object may move besides (m²); 245 samples
rest_var(6.21e-06).  % how far one that stood still as it vanished may move (m²); 943 samples
height_var(1e-08).  % how far a hidden object's height may move (m² a frame); 1,195 samples
grip_reach(0.1482).  % how far (table plane) a hand's grip may be from what it takes (m); 52 samples
grip_height(0.1178).  % how far above its top (m); 52 samples
occluder_rise(0.009905).  % how far below its centre (m); 52 samples
grip_drop(0.02117).  % how far what a hand holds is below its grip (m); 2,440 samples
grip_rise(0.001213).  % how far a hand's grip rises in a frame when it lifts (m); 706 samples
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
hides(ball, 0.0007498).  % 16,002
hides(bottle, 8.237e-05).  % 12,139
hides(bowl, 0.1708).  % 11,004
hides(box, 0.2189).  % 27,197
hides(can, 0.0001385).  % 7,217
hides(cup, 0.1013).  % 20,745
hides(mug, 0.1334).  % 22,127
hides(skin, 0.4984).  % 4,599
hidden_share(ball, 0.2388).  % 45,359
hidden_share(bottle, 0.1493).  % 2,201
hidden_share(bowl, 0.05411).  % 3,121
hidden_share(box, 0.01854).  % 9,383
hidden_share(can, 0.1514).  % 4,900
hidden_share(cup, 0.161).  % 12,753
hidden_share(mug, 0.07616).  % 11,684
hidden_share(skin, 3.161e-05).  % 31,629
carries(bowl, 0.5).  % 2
carries(box, 0.3333).  % 1
carries(skin, 0.9982).  % 1,100
carrier(skin).
can_occlude(O) := category(O, C), hides(C, P), P >= 0.01, \+ is_carrier(O).
is_carrier(O) := category(O, C), carrier(C).
hand_known := object(O), is_carrier(O).
can_be_occluded(A) := category(A, C), hidden_share(C, P), P >= 0.01.

:- include('too/too_learned_glue.pl').
% The onset reach (m): 90% of the 58 onsets in the data (6 far out left out) were within 0.0887 m; times 2.0.
onset_reach(0.1774).
% The reach of the kinds with onsets enough for one of their own.
onset_reach(box, 0.1367).  % 32 onsets, (5 far out left out) 90% within 0.06837 m
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

% occluder(Occluded, Occluder):t+1: 119 clauses, 21825 groundings, training log-likelihood -4961.2 (mean -0.110256 per grounding), 173 parameters.
occluder(Occluded, Occluder):t+1 ~ finite([P1:true, P2:false]) :=
    pair(Occluded, Occluder):t+1,
    (   distance(Occluded, Occluder):t+1 ~= Distance
    ->  (   kind(Occluder):t+1 ~= ball
        ->  (   moved(Occluder):t+1 ~= Moved
            ->  (   Moved < 0.004
                ->  % n = 762 (weight 3534), log-likelihood -0.999576, finite
                    P1 = 0.000282805,
                    P2 = 0.999717195
                ;   % n = 499 (weight 631), log-likelihood -23.036, logistic
                    logistic([Distance], [-36.8787, 0.750687], P1),
                    P2 is 1-P1
                )
            ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                logistic([Distance], [-38.61, -1.51058], P1),
                P2 is 1-P1
            )
        ;   kind(Occluder):t+1 ~= bottle
        ->  % n = 892 (weight 3780), log-likelihood -0.999603, finite
            P1 = 0.00026441,
            P2 = 0.99973559
        ;   kind(Occluder):t+1 ~= bowl
        ->  (   kind(Occluded):t+1 ~= ball
            ->  (   occluded_by(Occluded, Occluder):t
                ->  (   rise(Occluded, Occluder):t+1 ~= Rise
                    ->  (   Rise < 0.0
                        ->  % n = 44 (weight 140), log-likelihood -0.989403, finite
                            P1 = 0.99295775,
                            P2 = 0.00704225
                        ;   Rise < 0.1
                        ->  % n = 498 (weight 1694), log-likelihood -0.999115, finite
                            P1 = 0.999410377,
                            P2 = 0.000589623
                        ;   % n = 29 (weight 45), log-likelihood -19.4852, finite
                            P1 = 0.829787,
                            P2 = 0.170213
                        )
                    ;   % n = 0, too few groundings for a model of its own: the parent's model, finite
                        P1 = 0.99574694,
                        P2 = 0.00425306
                    )
                ;   (   rise(Occluded, Occluder):t+1 ~= Rise4
                    ->  (   Rise4 < 0.0
                        ->  % n = 144 (weight 200), log-likelihood -1.43806, logistic
                            logistic([Distance], [-167.164, 12.8491], P1),
                            P2 is 1-P1
                        ;   Rise4 < 0.1
                        ->  (   seen(Occluder):t
                            ->  (   moved(Occluder):t+1 ~= Moved3
                                ->  (   Moved3 < 0.004
                                    ->  % n = 1102 (weight 1722), log-likelihood -1135.24, logistic
                                        logistic([Distance], [-6.84491, 0.773583], P1),
                                        P2 is 1-P1
                                    ;   % n = 423 (weight 475), log-likelihood -307.377, logistic
                                        logistic([Distance], [-9.87637, 0.539637], P1),
                                        P2 is 1-P1
                                    )
                                ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                                    logistic([Distance], [-7.31462, 0.702791], P1),
                                    P2 is 1-P1
                                )
                            ;   % n = 32 (weight 56), log-likelihood -19.1181, finite
                                P1 = 0.12069,
                                P2 = 0.87931
                            )
                        ;   (   moved(Occluder):t+1 ~= Moved6
                            ->  (   Moved6 < 0.004
                                ->  % n = 18, log-likelihood -0.923279, finite
                                    P1 = 0.95,
                                    P2 = 0.05
                                ;   % n = 35, log-likelihood -23.9028, finite
                                    P1 = 0.567568,
                                    P2 = 0.432432
                                )
                            ;   % n = 0, too few groundings for a model of its own: the parent's model, finite
                                P1 = 0.709091,
                                P2 = 0.290909
                            )
                        )
                    ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                        logistic([Distance], [-9.38992, 0.863955], P1),
                        P2 is 1-P1
                    )
                )
            ;   kind(Occluded):t+1 ~= bottle
            ->  % n = 27 (weight 39), log-likelihood -0.963012, finite
                P1 = 0.0243902,
                P2 = 0.9756098
            ;   kind(Occluded):t+1 ~= bowl
            ->  % n = 1 (weight 5), too few groundings for a model of its own: the parent's model, log-likelihood -6.39517, logistic
                logistic([Distance], [-22.1887, 1.71842], P1),
                P2 is 1-P1
            ;   kind(Occluded):t+1 ~= box
            ->  % n = 66 (weight 222), log-likelihood -0.99329, finite
                P1 = 0.00446429,
                P2 = 0.99553571
            ;   kind(Occluded):t+1 ~= can
            ->  % n = 38 (weight 46), log-likelihood -0.968457, finite
                P1 = 0.0208333,
                P2 = 0.9791667
            ;   kind(Occluded):t+1 ~= cup
            ->  % n = 238 (weight 538), log-likelihood -0.99722, finite
                P1 = 0.00185185,
                P2 = 0.99814815
            ;   kind(Occluded):t+1 ~= mug
            ->  % n = 144 (weight 408), log-likelihood -0.996337, finite
                P1 = 0.00243902,
                P2 = 0.99756098
            ;   kind(Occluded):t+1 ~= skin
            ->  % n = 21 (weight 85), log-likelihood -0.98267, finite
                P1 = 0.0114943,
                P2 = 0.9885057
            ;   \+ kind(Occluded):t+1 ~= _
            ->  % n = 0, too few groundings for a model of its own: the parent's model, logistic
                logistic([Distance], [-22.1887, 1.71842], P1),
                P2 is 1-P1
            )
        ;   kind(Occluder):t+1 ~= box
        ->  (   kind(Occluded):t+1 ~= ball
            ->  (   occluded_by(Occluded, Occluder):t
                ->  (   moved(Occluder):t+1 ~= Moved9
                    ->  (   Moved9 < 0.004
                        ->  % n = 508 (weight 2540), log-likelihood -0.99941, finite
                            P1 = 0.999606609,
                            P2 = 0.000393391
                        ;   (   lift(Occluder):t+1 ~= Lift
                            ->  % n = 714 (weight 946), log-likelihood -63.0583, logistic
                                logistic([Distance, Lift], [349.949, -59.2206, 2.6073], P1),
                                P2 is 1-P1
                            ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                                logistic([Distance], [413.766, 2.17365], P1),
                                P2 is 1-P1
                            )
                        )
                    ;   % n = 0, too few groundings for a model of its own: the parent's model, finite
                        P1 = 0.99397936,
                        P2 = 0.00602064
                    )
                ;   (   lost_anywhere(Occluded):t
                    ->  (   seen(Occluder):t
                        ->  % n = 77 (weight 281), log-likelihood -0.994691, finite
                            P1 = 0.00353357,
                            P2 = 0.99646643
                        ;   % n = 16 (weight 20), log-likelihood -12.2327, finite
                            P1 = 0.318182,
                            P2 = 0.681818
                        )
                    ;   (   rise(Occluded, Occluder):t+1 ~= Rise8
                        ->  (   Rise8 < 0.0
                            ->  % n = 0, too few groundings for a model of its own: the parent's model, logistic
                                logistic([Distance], [-19.502, 1.60612], P1),
                                P2 is 1-P1
                            ;   Rise8 < 0.1
                            ->  (   seen(Occluder):t
                                ->  (   moved(Occluder):t+1 ~= Moved12
                                    ->  (   Moved12 < 0.004
                                        ->  % n = 1760 (weight 2160), log-likelihood -1083.79, logistic
                                            logistic([Distance], [-21.7408, 1.78003], P1),
                                            P2 is 1-P1
                                        ;   % n = 525 (weight 549), log-likelihood -339.513, logistic
                                            logistic([Distance], [-7.54598, 1.10793], P1),
                                            P2 is 1-P1
                                        )
                                    ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                                        logistic([Distance], [-17.0531, 1.63647], P1),
                                        P2 is 1-P1
                                    )
                                ;   % n = 56 (weight 76), log-likelihood -45.5673, logistic
                                    logistic([Distance], [-31.4441, 0.619082], P1),
                                    P2 is 1-P1
                                )
                            ;   % n = 97, log-likelihood -20.9532, logistic
                                logistic([Distance], [-76.0011, 1.65423], P1),
                                P2 is 1-P1
                            )
                        ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                            logistic([Distance], [-19.502, 1.60612], P1),
                            P2 is 1-P1
                        )
                    )
                )
            ;   kind(Occluded):t+1 ~= bottle
            ->  % n = 30 (weight 54), log-likelihood -0.972999, finite
                P1 = 0.0178571,
                P2 = 0.9821429
            ;   kind(Occluded):t+1 ~= bowl
            ->  % n = 33 (weight 77), log-likelihood -0.980905, finite
                P1 = 0.0126582,
                P2 = 0.9873418
            ;   kind(Occluded):t+1 ~= box
            ->  % n = 181 (weight 677), log-likelihood -0.997789, finite
                P1 = 0.00147275,
                P2 = 0.99852725
            ;   kind(Occluded):t+1 ~= can
            ->  (   rise(Occluded, Occluder):t+1 ~= Rise12
                ->  (   Rise12 < 0.0
                    ->  % n = 50 (weight 90), log-likelihood -0.983616, finite
                        P1 = 0.0108696,
                        P2 = 0.9891304
                    ;   Rise12 < 0.1
                    ->  (   moved(Occluder):t+1 ~= Moved15
                        ->  (   Moved15 < 0.004
                            ->  % n = 616 (weight 1076), log-likelihood -0.998608, finite
                                P1 = 0.999072356,
                                P2 = 0.000927644
                            ;   % n = 164 (weight 192), log-likelihood -53.6584, logistic
                                logistic([Distance], [-52.3077, 3.18371], P1),
                                P2 is 1-P1
                            )
                        ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                            logistic([Distance], [-77.781, 5.36624], P1),
                            P2 is 1-P1
                        )
                    ;   % n = 22 (weight 26), log-likelihood -12.7666, finite
                        P1 = 0.214286,
                        P2 = 0.785714
                    )
                ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                    logistic([Distance], [-96.6718, 5.26237], P1),
                    P2 is 1-P1
                )
            ;   kind(Occluded):t+1 ~= cup
            ->  (   moved(Occluder):t+1 ~= Moved18
                ->  (   Moved18 < 0.004
                    ->  (   lost_anywhere(Occluded):t
                        ->  % n = 6 (weight 30), log-likelihood -0.952461, finite
                            P1 = 0.03125,
                            P2 = 0.96875
                        ;   (   rise(Occluded, Occluder):t+1 ~= Rise16
                            ->  (   Rise16 < 0.0
                                ->  % n = 3 (weight 15), log-likelihood -0.909369, finite
                                    P1 = 0.0588235,
                                    P2 = 0.9411765
                                ;   Rise16 < 0.1
                                ->  % n = 1396 (weight 2528), log-likelihood -321.777, logistic
                                    logistic([Distance], [-107.115, 6.41678], P1),
                                    P2 is 1-P1
                                ;   % n = 3 (weight 11), log-likelihood -0.88047, finite
                                    P1 = 0.0769231,
                                    P2 = 0.9230769
                                )
                            ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                                logistic([Distance], [-96.6907, 5.92485], P1),
                                P2 is 1-P1
                            )
                        )
                    ;   (   occluded_by(Occluded, Occluder):t
                        ->  % n = 140 (weight 168), log-likelihood -16.4998, logistic
                            logistic([Distance], [130.983, 1.90974], P1),
                            P2 is 1-P1
                        ;   % n = 148 (weight 180), log-likelihood -105.859, logistic
                            logistic([Distance], [-16.5021, 0.270117], P1),
                            P2 is 1-P1
                        )
                    )
                ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                    logistic([Distance], [-67.9635, 4.37842], P1),
                    P2 is 1-P1
                )
            ;   kind(Occluded):t+1 ~= mug
            ->  (   occluded_by(Occluded, Occluder):t
                ->  % n = 95 (weight 335), log-likelihood -7.11504, finite
                    P1 = 0.99406528,
                    P2 = 0.00593472
                ;   (   moved(Occluder):t+1 ~= Moved21
                    ->  (   Moved21 < 0.004
                        ->  % n = 189 (weight 589), log-likelihood -181.771, logistic
                            logistic([Distance], [-162.109, 1.41138], P1),
                            P2 is 1-P1
                        ;   (   lift(Occluder):t+1 ~= Lift2
                            ->  % n = 125 (weight 177), log-likelihood -46.9645, logistic
                                logistic([Distance, Lift2], [-17.513, -281.182, -1.08045], P1),
                                P2 is 1-P1
                            ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                                logistic([Distance], [-20.2505, -0.892065], P1),
                                P2 is 1-P1
                            )
                        )
                    ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                        logistic([Distance], [-46.0265, -0.360568], P1),
                        P2 is 1-P1
                    )
                )
            ;   kind(Occluded):t+1 ~= skin
            ->  % n = 287 (weight 1003), log-likelihood -0.998507, finite
                P1 = 0.000995025,
                P2 = 0.999004975
            ;   \+ kind(Occluded):t+1 ~= _
            ->  % n = 0, too few groundings for a model of its own: the parent's model, logistic
                logistic([Distance], [-53.0027, 2.77595], P1),
                P2 is 1-P1
            )
        ;   kind(Occluder):t+1 ~= can
        ->  % n = 497 (weight 1869), log-likelihood -0.999198, finite
            P1 = 0.000534474,
            P2 = 0.999465526
        ;   kind(Occluder):t+1 ~= cup
        ->  (   kind(Occluded):t+1 ~= ball
            ->  (   seen(Occluder):t
                ->  (   lift(Occluder):t+1 ~= Lift4
                    ->  (   rise(Occluded, Occluder):t+1 ~= Rise20
                        ->  (   Rise20 < 0.0
                            ->  % n = 62 (weight 182), log-likelihood -0.991828, finite
                                P1 = 0.99456522,
                                P2 = 0.00543478
                            ;   Rise20 < 0.1
                            ->  % n = 1808 (weight 3272), log-likelihood -66.387, logistic
                                logistic([Distance, Lift4], [-178.948, -730.167, 7.7175], P1),
                                P2 is 1-P1
                            ;   (   moved(Occluder):t+1 ~= Moved24
                                ->  (   Moved24 < 0.004
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
                            logistic([Distance, Lift4], [-150.414, -310.936, 6.29677], P1),
                            P2 is 1-P1
                        )
                    ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                        logistic([Distance], [-132.369, 5.61729], P1),
                        P2 is 1-P1
                    )
                ;   % n = 13 (weight 17), log-likelihood -11.7544, finite
                    P1 = 0.526316,
                    P2 = 0.473684
                )
            ;   kind(Occluded):t+1 ~= bottle
            ->  % n = 0, too few groundings for a model of its own: the parent's model, logistic
                logistic([Distance], [-51.4069, 2.37922], P1),
                P2 is 1-P1
            ;   kind(Occluded):t+1 ~= bowl
            ->  % n = 0, too few groundings for a model of its own: the parent's model, logistic
                logistic([Distance], [-51.4069, 2.37922], P1),
                P2 is 1-P1
            ;   kind(Occluded):t+1 ~= box
            ->  % n = 29 (weight 117), log-likelihood -0.987348, finite
                P1 = 0.00840336,
                P2 = 0.99159664
            ;   kind(Occluded):t+1 ~= can
            ->  % n = 1, too few groundings for a model of its own: the parent's model, log-likelihood -0.473599, logistic
                logistic([Distance], [-51.4069, 2.37922], P1),
                P2 is 1-P1
            ;   kind(Occluded):t+1 ~= cup
            ->  % n = 8 (weight 28), log-likelihood -0.949243, finite
                P1 = 0.0333333,
                P2 = 0.9666667
            ;   kind(Occluded):t+1 ~= mug
            ->  % n = 88 (weight 376), log-likelihood -0.996027, finite
                P1 = 0.0026455,
                P2 = 0.9973545
            ;   kind(Occluded):t+1 ~= skin
            ->  % n = 289 (weight 937), log-likelihood -0.998402, finite
                P1 = 0.00106496,
                P2 = 0.99893504
            ;   \+ kind(Occluded):t+1 ~= _
            ->  % n = 0, too few groundings for a model of its own: the parent's model, logistic
                logistic([Distance], [-51.4069, 2.37922], P1),
                P2 is 1-P1
            )
        ;   kind(Occluder):t+1 ~= mug
        ->  (   kind(Occluded):t+1 ~= ball
            ->  (   occluded_by(Occluded, Occluder):t
                ->  (   lift(Occluder):t+1 ~= Lift6
                    ->  % n = 726 (weight 2934), log-likelihood -13.9897, logistic
                        logistic([Distance, Lift6], [283.064, -1017.29, 8.2548], P1),
                        P2 is 1-P1
                    ;   % n = 0, too few groundings for a model of its own: the parent's model, finite
                        P1 = 0.99625341,
                        P2 = 0.00374659
                    )
                ;   (   moved(Occluder):t+1 ~= Moved27
                    ->  (   Moved27 < 0.004
                        ->  % n = 1325 (weight 1365), log-likelihood -95.7526, logistic
                            logistic([Distance], [689.175, -5.1016], P1),
                            P2 is 1-P1
                        ;   (   lift(Occluder):t+1 ~= Lift8
                            ->  % n = 140 (weight 144), log-likelihood -55.362, logistic
                                logistic([Distance, Lift8], [-92.4703, -219.152, 3.50723], P1),
                                P2 is 1-P1
                            ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                                logistic([Distance], [-88.6716, 3.41308], P1),
                                P2 is 1-P1
                            )
                        )
                    ;   % n = 0, too few groundings for a model of its own: the parent's model, finite
                        P1 = 0.9417604,
                        P2 = 0.0582396
                    )
                )
            ;   kind(Occluded):t+1 ~= bottle
            ->  % n = 0, too few groundings for a model of its own: the parent's model, logistic
                logistic([Distance], [-81.7109, 4.22673], P1),
                P2 is 1-P1
            ;   kind(Occluded):t+1 ~= bowl
            ->  % n = 4 (weight 20), log-likelihood -0.133948, logistic
                logistic([Distance], [-61.7656, 4.74576], P1),
                P2 is 1-P1
            ;   kind(Occluded):t+1 ~= box
            ->  % n = 8 (weight 36), log-likelihood -0.960057, finite
                P1 = 0.0263158,
                P2 = 0.9736842
            ;   kind(Occluded):t+1 ~= can
            ->  % n = 0, too few groundings for a model of its own: the parent's model, logistic
                logistic([Distance], [-81.7109, 4.22673], P1),
                P2 is 1-P1
            ;   kind(Occluded):t+1 ~= cup
            ->  % n = 12, log-likelihood -0.889296, finite
                P1 = 0.0714286,
                P2 = 0.9285714
            ;   kind(Occluded):t+1 ~= mug
            ->  % n = 51 (weight 119), log-likelihood -0.987558, finite
                P1 = 0.00826446,
                P2 = 0.99173554
            ;   kind(Occluded):t+1 ~= skin
            ->  % n = 348 (weight 1188), log-likelihood -0.998739, finite
                P1 = 0.000840336,
                P2 = 0.999159664
            ;   \+ kind(Occluded):t+1 ~= _
            ->  % n = 0, too few groundings for a model of its own: the parent's model, logistic
                logistic([Distance], [-81.7109, 4.22673], P1),
                P2 is 1-P1
            )
        ;   kind(Occluder):t+1 ~= skin
        ->  (   kind(Occluded):t+1 ~= ball
            ->  (   occluded_by(Occluded, Occluder):t
                ->  % n = 321 (weight 413), log-likelihood -7.32547, finite
                    P1 = 0.99518072,
                    P2 = 0.00481928
                ;   % n = 664 (weight 708), log-likelihood -292.605, logistic
                    logistic([Distance], [-32.5918, 2.32064], P1),
                    P2 is 1-P1
                )
            ;   kind(Occluded):t+1 ~= bottle
            ->  (   rise(Occluded, Occluder):t+1 ~= Rise24
                ->  (   Rise24 < 0.0
                    ->  % n = 3, too few groundings for a model of its own: the parent's model, log-likelihood -4.04554, logistic
                        logistic([Distance], [-15.4811, 3.20644], P1),
                        P2 is 1-P1
                    ;   Rise24 < 0.1
                    ->  % n = 168 (weight 204), log-likelihood -15.0587, logistic
                        logistic([Distance], [-124.417, 4.47785], P1),
                        P2 is 1-P1
                    ;   (   occluded_by(Occluded, Occluder):t
                        ->  % n = 135 (weight 199), log-likelihood -0.992521, finite
                            P1 = 0.99502488,
                            P2 = 0.00497512
                        ;   (   moved(Occluder):t+1 ~= Moved30
                            ->  (   Moved30 < 0.004
                                ->  % n = 65, log-likelihood -0.977462, finite
                                    P1 = 0.9850746,
                                    P2 = 0.0149254
                                ;   % n = 110, log-likelihood -47.3721, finite
                                    P1 = 0.839286,
                                    P2 = 0.160714
                                )
                            ;   % n = 0, too few groundings for a model of its own: the parent's model, finite
                                P1 = 0.898305,
                                P2 = 0.101695
                            )
                        )
                    )
                ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                    logistic([Distance], [-15.4811, 3.20644], P1),
                    P2 is 1-P1
                )
            ;   kind(Occluded):t+1 ~= bowl
            ->  (   seen(Occluded):t
                ->  % n = 12, log-likelihood -6.78654, finite
                    P1 = 0.285714,
                    P2 = 0.714286
                ;   (   occluded_by(Occluded, Occluder):t
                    ->  (   lift(Occluder):t+1 ~= Lift10
                        ->  % n = 107 (weight 151), log-likelihood -3.50207, logistic
                            logistic([Distance, Lift10], [-43.8702, -136.342, 5.90692], P1),
                            P2 is 1-P1
                        ;   % n = 0, too few groundings for a model of its own: the parent's model, finite
                            P1 = 0.9738562,
                            P2 = 0.0261438
                        )
                    ;   (   moved(Occluder):t+1 ~= Moved33
                        ->  (   Moved33 < 0.004
                            ->  % n = 32 (weight 36), log-likelihood -3.57863, logistic
                                logistic([Distance], [-614.349, 58.6958], P1),
                                P2 is 1-P1
                            ;   % n = 94, log-likelihood -31.8871, finite
                                P1 = 0.885417,
                                P2 = 0.114583
                            )
                        ;   % n = 0, too few groundings for a model of its own: the parent's model, finite
                            P1 = 0.878788,
                            P2 = 0.121212
                        )
                    )
                )
            ;   kind(Occluded):t+1 ~= box
            ->  % n = 331 (weight 391), log-likelihood -110.485, logistic
                logistic([Distance], [-41.4358, 3.47257], P1),
                P2 is 1-P1
            ;   kind(Occluded):t+1 ~= can
            ->  % n = 166 (weight 182), log-likelihood -33.7114, logistic
                logistic([Distance], [-46.5683, 4.01695], P1),
                P2 is 1-P1
            ;   kind(Occluded):t+1 ~= cup
            ->  (   lift(Occluder):t+1 ~= Lift12
                ->  % n = 1072 (weight 1216), log-likelihood -147.964, logistic
                    logistic([Distance, Lift12], [-32.2268, -83.7825, 5.5547], P1),
                    P2 is 1-P1
                ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                    logistic([Distance], [-27.0102, 4.83877], P1),
                    P2 is 1-P1
                )
            ;   kind(Occluded):t+1 ~= mug
            ->  (   lift(Occluder):t+1 ~= Lift14
                ->  (   seen(Occluded):t
                    ->  % n = 19, log-likelihood -0.0645829, logistic
                        logistic([Distance, Lift14], [-25.5456, -426.638, -5.7371], P1),
                        P2 is 1-P1
                    ;   % n = 835 (weight 971), log-likelihood -116.082, logistic
                        logistic([Distance, Lift14], [-26.0618, -79.3199, 4.70736], P1),
                        P2 is 1-P1
                    )
                ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                    logistic([Distance], [-21.6677, 4.05418], P1),
                    P2 is 1-P1
                )
            ;   kind(Occluded):t+1 ~= skin
            ->  % n = 0, too few groundings for a model of its own: the parent's model, logistic
                logistic([Distance], [-29.1154, 3.56248], P1),
                P2 is 1-P1
            ;   \+ kind(Occluded):t+1 ~= _
            ->  % n = 0, too few groundings for a model of its own: the parent's model, logistic
                logistic([Distance], [-29.1154, 3.56248], P1),
                P2 is 1-P1
            )
        ;   \+ kind(Occluder):t+1 ~= _
        ->  % n = 0, too few groundings for a model of its own: the parent's model, logistic
            logistic([Distance], [-38.732, 2.5785], P1),
            P2 is 1-P1
        )
    ;   % n = 0, too few groundings for a model of its own: the parent's model, finite
        P1 = 0.551501,
        P2 = 0.448499
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

% released(Held):t+1: 3 clauses, 2442 groundings, training log-likelihood -73.6101 (mean -0.0301434 per grounding), 6 parameters.
released(Held):t+1 ~ finite([P1:true, P2:false]) :=
    carried(Held):t+1,
    (   height(Held):t+1 ~= Height
    ->  (   highest(Held):t+1 ~= Highest
        ->  % n = 2442, log-likelihood -73.6101, logistic
            logistic([Height, Highest], [-102.528, 62.5973, -9.04212], P1),
            P2 is 1-P1
        ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
            logistic([Height], [-48.036, -1.50418], P1),
            P2 is 1-P1
        )
    ;   % n = 0, too few groundings for a model of its own: the parent's model, finite
        P1 = 0.0249591,
        P2 = 0.9750409
    ).

:- include('too/too_motion.pl').
