/*  too_learned_hindsight.pl -- the theory of occlusion with rules learned from experience.

    Written by `anchoring learn-theory`: a tree learned (ddc learn) from
    data_hindsight.pl: 13241 groundings of occluder(A, O):t+1,
    88 clauses, training log-likelihood -2809.66;
    and one for released(A):t+1 from 982 frames a hand held an object
    (3 clauses, training log-likelihood -33.9081);
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
obs_var(3.822e-06).  % the measurement noise of a perceived position (m², per axis); 91,279 samples
motion_var(3.184e-05).  % how far a perceived object moves in a frame (m², per axis); 122,427 samples
reappear_var(0.001354).  % where a hidden object is seen again, around its belief (m²); 1,267 samples
lost_var(0.07154).  % the same for an object lost while the camera saw nothing (m²); 8,187 samples
follow_keep(0.999).  % the fraction of its offset from its occluder a hidden object keeps; 25 samples
follow_var(1.571e-07).  % the jitter of that offset per frame (m²); 25 samples
coast_keep(0.8678).  % the fraction of its velocity a hidden object under nothing keeps; 37 samples
wander_var(0.0003492).  % how far such an object may move besides (m²); 37 samples
rest_var(1.6e-06).  % how far one that stood still as it vanished may move (m²); 84 samples
height_var(1e-08).  % how far a hidden object's height may move (m² a frame); 128 samples
grip_reach(0.06474).  % how far (table plane) a hand's grip may be from what it takes (m); 21 samples
grip_height(0.1377).  % how far above its top (m); 21 samples
occluder_rise(0.00425).  % how far below its centre (m); 21 samples
grip_drop(0.04065).  % how far what a hand holds is below its grip (m); 21 samples
grip_rise(0.00109).  % how far a hand's grip rises in a frame when it lifts (m); 277 samples
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
hides(ball, 0.0007442).  % 10,317
hides(bottle, 0.0001563).  % 6,398
hides(bowl, 0.04415).  % 6,816
hides(box, 0.2081).  % 19,259
hides(can, 0.0002088).  % 4,788
hides(cup, 0.09245).  % 15,661
hides(mug, 0.1656).  % 16,123
hides(skin, 0.328).  % 3,605
hidden_share(ball, 0.1959).  % 33,762
hidden_share(bottle, 0.108).  % 1,792
hidden_share(bowl, 0.02357).  % 4,240
hidden_share(box, 0.01033).  % 10,933
hidden_share(can, 0.1319).  % 3,820
hidden_share(cup, 0.1328).  % 12,998
hidden_share(mug, 0.03258).  % 11,264
hidden_share(skin, 0.0002404).  % 4,158
carries(box, 0.875).  % 6
carries(skin, 0.9972).  % 529
carrier(skin).
can_occlude(O) := category(O, C), hides(C, P), P >= 0.01, \+ is_carrier(O).
is_carrier(O) := category(O, C), carrier(C).
hand_known := object(O), is_carrier(O).
can_be_occluded(A) := category(A, C), hidden_share(C, P), P >= 0.01.

:- include('too/too_learned_glue.pl').
% The onset reach (m): 90% of the 37 onsets in the data (1 far out left out) were within 0.05909 m; times 2.0.
onset_reach(0.1182).
% The reach of the kinds with onsets enough for one of their own.
onset_reach(box, 0.0879).  % 14 onsets, (1 far out left out) 90% within 0.04395 m

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

% occluder(Occluded, Occluder):t+1: 88 clauses, 13241 groundings, training log-likelihood -2809.66 (mean -0.109821 per grounding), 115 parameters.
occluder(Occluded, Occluder):t+1 ~ finite([P1:true, P2:false]) :=
    pair(Occluded, Occluder):t+1,
    (   distance(Occluded, Occluder):t+1 ~= Distance
    ->  (   kind(Occluder):t+1 ~= ball
        ->  % n = 300 (weight 757), log-likelihood -27.3563, logistic
            logistic([Distance], [-27.6925, -1.55973], P1),
            P2 is 1-P1
        ;   kind(Occluder):t+1 ~= bottle
        ->  % n = 132 (weight 400), log-likelihood -0.996265, finite
            P1 = 0.00248756,
            P2 = 0.99751244
        ;   kind(Occluder):t+1 ~= bowl
        ->  (   occluded_by(Occluded, Occluder):t
            ->  % n = 123 (weight 291), log-likelihood -0.994873, finite
                P1 = 0.99658703,
                P2 = 0.00341297
            ;   (   kind(Occluded):t+1 ~= ball
                ->  (   lost_anywhere(Occluded):t
                    ->  % n = 83 (weight 283), log-likelihood -0.994729, finite
                        P1 = 0.00350877,
                        P2 = 0.99649123
                    ;   (   moved(Occluder):t+1 ~= Moved
                        ->  (   Moved < 0.004
                            ->  (   seen(Occluder):t
                                ->  (   lift(Occluder):t+1 ~= Lift
                                    ->  % n = 210 (weight 534), log-likelihood -208.57, logistic
                                        logistic([Distance, Lift], [44.712, -1363.58, -2.50434], P1),
                                        P2 is 1-P1
                                    ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                                        logistic([Distance], [45.339, -2.51388], P1),
                                        P2 is 1-P1
                                    )
                                ;   % n = 4 (weight 20), log-likelihood -0.9304, finite
                                    P1 = 0.0454545,
                                    P2 = 0.9545455
                                )
                            ;   % n = 189 (weight 241), log-likelihood -113.033, finite
                                P1 = 0.18107,
                                P2 = 0.81893
                            )
                        ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                            logistic([Distance], [15.0682, -1.95117], P1),
                            P2 is 1-P1
                        )
                    )
                ;   kind(Occluded):t+1 ~= bottle
                ->  % n = 23 (weight 35), log-likelihood -0.958964, finite
                    P1 = 0.027027,
                    P2 = 0.972973
                ;   kind(Occluded):t+1 ~= bowl
                ->  % n = 141 (weight 249), log-likelihood -6.81632, finite
                    P1 = 0.00796813,
                    P2 = 0.99203187
                ;   kind(Occluded):t+1 ~= box
                ->  (   seen(Occluded):t
                    ->  % n = 20, log-likelihood -12.2327, finite
                        P1 = 0.318182,
                        P2 = 0.681818
                    ;   % n = 58 (weight 90), log-likelihood -5.78476, finite
                        P1 = 0.0217391,
                        P2 = 0.9782609
                    )
                ;   kind(Occluded):t+1 ~= can
                ->  % n = 9, too few groundings for a model of its own: the parent's model, log-likelihood -0.978042, finite
                    P1 = 0.102975,
                    P2 = 0.897025
                ;   kind(Occluded):t+1 ~= cup
                ->  % n = 73 (weight 185), log-likelihood -0.991959, finite
                    P1 = 0.00534759,
                    P2 = 0.99465241
                ;   kind(Occluded):t+1 ~= mug
                ->  % n = 36 (weight 72), log-likelihood -0.979607, finite
                    P1 = 0.0135135,
                    P2 = 0.9864865
                ;   kind(Occluded):t+1 ~= skin
                ->  % n = 4 (weight 8), too few groundings for a model of its own: the parent's model, log-likelihood -0.869371, finite
                    P1 = 0.102975,
                    P2 = 0.897025
                ;   \+ kind(Occluded):t+1 ~= _
                ->  % n = 0, too few groundings for a model of its own: the parent's model, finite
                    P1 = 0.102975,
                    P2 = 0.897025
                )
            )
        ;   kind(Occluder):t+1 ~= box
        ->  (   kind(Occluded):t+1 ~= ball
            ->  (   occluded_by(Occluded, Occluder):t
                ->  % n = 620 (weight 1944), log-likelihood -0.999229, finite
                    P1 = 0.999486125,
                    P2 = 0.000513875
                ;   (   lost_anywhere(Occluded):t
                    ->  % n = 126 (weight 470), log-likelihood -7.45534, finite
                        P1 = 0.00423729,
                        P2 = 0.99576271
                    ;   (   moved(Occluder):t+1 ~= Moved3
                        ->  (   Moved3 < 0.004
                            ->  (   seen(Occluder):t
                                ->  % n = 1221 (weight 1473), log-likelihood -767.101, finite
                                    P1 = 0.784407,
                                    P2 = 0.215593
                                ;   % n = 28, log-likelihood -0.949243, finite
                                    P1 = 0.9666667,
                                    P2 = 0.0333333
                                )
                            ;   % n = 386 (weight 406), log-likelihood -255.395, logistic
                                logistic([Distance], [-23.8456, 1.35117], P1),
                                P2 is 1-P1
                            )
                        ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                            logistic([Distance], [-8.38361, 1.3335], P1),
                            P2 is 1-P1
                        )
                    )
                )
            ;   kind(Occluded):t+1 ~= bottle
            ->  % n = 14 (weight 18), log-likelihood -0.923279, finite
                P1 = 0.05,
                P2 = 0.95
            ;   kind(Occluded):t+1 ~= bowl
            ->  % n = 34 (weight 78), log-likelihood -0.981145, finite
                P1 = 0.0125,
                P2 = 0.9875
            ;   kind(Occluded):t+1 ~= box
            ->  % n = 186 (weight 634), log-likelihood -0.99764, finite
                P1 = 0.00157233,
                P2 = 0.99842767
            ;   kind(Occluded):t+1 ~= can
            ->  (   occluded_by(Occluded, Occluder):t
                ->  % n = 128 (weight 440), log-likelihood -0.996603, finite
                    P1 = 0.99773756,
                    P2 = 0.00226244
                ;   (   lift(Occluder):t+1 ~= Lift2
                    ->  % n = 517 (weight 537), log-likelihood -31.2407, logistic
                        logistic([Distance, Lift2], [-173.354, 78.1773, 7.19766], P1),
                        P2 is 1-P1
                    ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                        logistic([Distance], [-143.611, 6.242], P1),
                        P2 is 1-P1
                    )
                )
            ;   kind(Occluded):t+1 ~= cup
            ->  (   occluded_by(Occluded, Occluder):t
                ->  % n = 317 (weight 1545), log-likelihood -0.99903, finite
                    P1 = 0.999353588,
                    P2 = 0.000646412
                ;   (   moved(Occluder):t+1 ~= Moved6
                    ->  (   Moved6 < 0.004
                        ->  (   lost_anywhere(Occluded):t
                            ->  % n = 1 (weight 5), too few groundings for a model of its own: the parent's model, log-likelihood -121.818, logistic
                                logistic([Distance], [162.271, -4.9563], P1),
                                P2 is 1-P1
                            ;   % n = 547 (weight 771), log-likelihood -107.698, logistic
                                logistic([Distance], [280.231, -9.11262], P1),
                                P2 is 1-P1
                            )
                        ;   % n = 62 (weight 66), log-likelihood -31.3121, finite
                            P1 = 0.191176,
                            P2 = 0.808824
                        )
                    ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                        logistic([Distance], [110.663, -3.49443], P1),
                        P2 is 1-P1
                    )
                )
            ;   kind(Occluded):t+1 ~= mug
            ->  (   moved(Occluder):t+1 ~= Moved9
                ->  (   Moved9 < 0.004
                    ->  (   rise(Occluded, Occluder):t+1 ~= Rise
                        ->  (   Rise < 0.0
                            ->  % n = 18 (weight 90), log-likelihood -0.983616, finite
                                P1 = 0.0108696,
                                P2 = 0.9891304
                            ;   Rise < 0.1
                            ->  % n = 176 (weight 300), log-likelihood -4.8972, logistic
                                logistic([Distance], [-364.916, 13.668], P1),
                                P2 is 1-P1
                            ;   % n = 3 (weight 15), log-likelihood -0.909369, finite
                                P1 = 0.0588235,
                                P2 = 0.9411765
                            )
                        ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                            logistic([Distance], [-408.735, 13.3499], P1),
                            P2 is 1-P1
                        )
                    ;   % n = 91 (weight 111), log-likelihood -26.9899, logistic
                        logistic([Distance], [-120.78, 2.7692], P1),
                        P2 is 1-P1
                    )
                ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                    logistic([Distance], [-331.364, 10.356], P1),
                    P2 is 1-P1
                )
            ;   kind(Occluded):t+1 ~= skin
            ->  % n = 67 (weight 147), log-likelihood -0.989903, finite
                P1 = 0.00671141,
                P2 = 0.99328859
            ;   \+ kind(Occluded):t+1 ~= _
            ->  % n = 0, too few groundings for a model of its own: the parent's model, logistic
                logistic([Distance], [-52.4287, 2.63069], P1),
                P2 is 1-P1
            )
        ;   kind(Occluder):t+1 ~= can
        ->  % n = 98 (weight 462), log-likelihood -0.996764, finite
            P1 = 0.00215517,
            P2 = 0.99784483
        ;   kind(Occluder):t+1 ~= cup
        ->  (   kind(Occluded):t+1 ~= ball
            ->  (   lost_anywhere(Occluded):t
                ->  % n = 16 (weight 64), log-likelihood -12.2238, finite
                    P1 = 0.0606061,
                    P2 = 0.9393939
                ;   (   occluded_by(Occluded, Occluder):t
                    ->  % n = 413 (weight 1437), log-likelihood -0.998957, finite
                        P1 = 0.999305073,
                        P2 = 0.000694927
                    ;   (   moved(Occluder):t+1 ~= Moved12
                        ->  (   Moved12 < 0.004
                            ->  % n = 1138 (weight 1158), log-likelihood -59.2993, logistic
                                logistic([Distance], [-157.679, 5.86005], P1),
                                P2 is 1-P1
                            ;   (   seen(Occluder):t
                                ->  % n = 169, log-likelihood -59.7866, logistic
                                    logistic([Distance], [-51.9999, 2.77115], P1),
                                    P2 is 1-P1
                                ;   % n = 12, log-likelihood -0.889296, finite
                                    P1 = 0.0714286,
                                    P2 = 0.9285714
                                )
                            )
                        ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                            logistic([Distance], [-84.7194, 4.58077], P1),
                            P2 is 1-P1
                        )
                    )
                )
            ;   kind(Occluded):t+1 ~= bottle
            ->  % n = 3, too few groundings for a model of its own: the parent's model, log-likelihood -1.28188e-06, logistic
                logistic([Distance], [-203.855, 2.40082], P1),
                P2 is 1-P1
            ;   kind(Occluded):t+1 ~= bowl
            ->  % n = 28 (weight 76), log-likelihood -0.980659, finite
                P1 = 0.0128205,
                P2 = 0.9871795
            ;   kind(Occluded):t+1 ~= box
            ->  % n = 26 (weight 98), log-likelihood -0.984933, finite
                P1 = 0.01,
                P2 = 0.99
            ;   kind(Occluded):t+1 ~= can
            ->  % n = 14 (weight 22), log-likelihood -0.936312, finite
                P1 = 0.0416667,
                P2 = 0.9583333
            ;   kind(Occluded):t+1 ~= cup
            ->  % n = 445 (weight 1205), log-likelihood -0.998757, finite
                P1 = 0.0008285,
                P2 = 0.9991715
            ;   kind(Occluded):t+1 ~= mug
            ->  % n = 122 (weight 470), log-likelihood -0.996819, finite
                P1 = 0.00211864,
                P2 = 0.99788136
            ;   kind(Occluded):t+1 ~= skin
            ->  % n = 0, too few groundings for a model of its own: the parent's model, logistic
                logistic([Distance], [-203.855, 2.40082], P1),
                P2 is 1-P1
            ;   \+ kind(Occluded):t+1 ~= _
            ->  % n = 0, too few groundings for a model of its own: the parent's model, logistic
                logistic([Distance], [-203.855, 2.40082], P1),
                P2 is 1-P1
            )
        ;   kind(Occluder):t+1 ~= mug
        ->  (   kind(Occluded):t+1 ~= ball
            ->  (   moved(Occluder):t+1 ~= Moved15
                ->  (   Moved15 < 0.004
                    ->  (   occluded_by(Occluded, Occluder):t
                        ->  % n = 495 (weight 2475), log-likelihood -0.999394, finite
                            P1 = 0.999596286,
                            P2 = 0.000403714
                        ;   % n = 1299 (weight 1703), log-likelihood -149.194, logistic
                            logistic([Distance], [-75.3572, 4.80716], P1),
                            P2 is 1-P1
                        )
                    ;   (   occluded_by(Occluded, Occluder):t
                        ->  % n = 135 (weight 187), log-likelihood -0.992045, finite
                            P1 = 0.99470899,
                            P2 = 0.00529101
                        ;   % n = 218 (weight 246), log-likelihood -123.728, logistic
                            logistic([Distance], [-25.6523, 1.16867], P1),
                            P2 is 1-P1
                        )
                    )
                ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                    logistic([Distance], [-84.4573, 4.7483], P1),
                    P2 is 1-P1
                )
            ;   kind(Occluded):t+1 ~= bottle
            ->  % n = 0, too few groundings for a model of its own: the parent's model, logistic
                logistic([Distance], [-166.278, 4.15294], P1),
                P2 is 1-P1
            ;   kind(Occluded):t+1 ~= bowl
            ->  % n = 12 (weight 20), log-likelihood -0.9304, finite
                P1 = 0.0454545,
                P2 = 0.9545455
            ;   kind(Occluded):t+1 ~= box
            ->  % n = 116 (weight 360), log-likelihood -0.995851, finite
                P1 = 0.00276243,
                P2 = 0.99723757
            ;   kind(Occluded):t+1 ~= can
            ->  % n = 5 (weight 13), log-likelihood -0.896907, finite
                P1 = 0.0666667,
                P2 = 0.9333333
            ;   kind(Occluded):t+1 ~= cup
            ->  % n = 27 (weight 39), log-likelihood -0.963012, finite
                P1 = 0.0243902,
                P2 = 0.9756098
            ;   kind(Occluded):t+1 ~= mug
            ->  % n = 181 (weight 537), log-likelihood -0.997215, finite
                P1 = 0.00185529,
                P2 = 0.99814471
            ;   kind(Occluded):t+1 ~= skin
            ->  % n = 34 (weight 158), log-likelihood -0.990599, finite
                P1 = 0.00625,
                P2 = 0.99375
            ;   \+ kind(Occluded):t+1 ~= _
            ->  % n = 0, too few groundings for a model of its own: the parent's model, logistic
                logistic([Distance], [-166.278, 4.15294], P1),
                P2 is 1-P1
            )
        ;   kind(Occluder):t+1 ~= skin
        ->  (   kind(Occluded):t+1 ~= ball
            ->  (   occluded_by(Occluded, Occluder):t
                ->  % n = 185 (weight 241), log-likelihood -0.993816, finite
                    P1 = 0.99588477,
                    P2 = 0.00411523
                ;   % n = 271 (weight 279), log-likelihood -79.133, logistic
                    logistic([Distance], [-50.9977, 3.22695], P1),
                    P2 is 1-P1
                )
            ;   kind(Occluded):t+1 ~= bottle
            ->  % n = 623 (weight 445), log-likelihood -303.646, finite
                P1 = 0.573012,
                P2 = 0.426988
            ;   kind(Occluded):t+1 ~= bowl
            ->  % n = 188 (weight 216), log-likelihood -59.6192, logistic
                logistic([Distance], [-69.8543, 4.82865], P1),
                P2 is 1-P1
            ;   kind(Occluded):t+1 ~= box
            ->  (   occluded_by(Occluded, Occluder):t
                ->  % n = 78 (weight 102), log-likelihood -0.985515, finite
                    P1 = 0.99038462,
                    P2 = 0.00961538
                ;   % n = 133 (weight 165), log-likelihood -82.3579, logistic
                    logistic([Distance], [-52.6145, 2.27594], P1),
                    P2 is 1-P1
                )
            ;   kind(Occluded):t+1 ~= can
            ->  % n = 91 (weight 99), log-likelihood -11.3589, logistic
                logistic([Distance], [-69.0507, 5.26239], P1),
                P2 is 1-P1
            ;   kind(Occluded):t+1 ~= cup
            ->  (   occluded_by(Occluded, Occluder):t
                ->  % n = 136 (weight 176), log-likelihood -0.991552, finite
                    P1 = 0.99438202,
                    P2 = 0.00561798
                ;   (   rise(Occluded, Occluder):t+1 ~= Rise4
                    ->  (   Rise4 < 0.0
                        ->  % n = 0, too few groundings for a model of its own: the parent's model, finite
                            P1 = 0.772727,
                            P2 = 0.227273
                        ;   Rise4 < 0.1
                        ->  % n = 34 (weight 38), log-likelihood -6.09678, logistic
                            logistic([Distance], [1818.46, -18.468], P1),
                            P2 is 1-P1
                        ;   % n = 128 (weight 136), log-likelihood -67.7846, finite
                            P1 = 0.797101,
                            P2 = 0.202899
                        )
                    ;   % n = 0, too few groundings for a model of its own: the parent's model, finite
                        P1 = 0.772727,
                        P2 = 0.227273
                    )
                )
            ;   kind(Occluded):t+1 ~= mug
            ->  % n = 421 (weight 501), log-likelihood -30.7929, logistic
                logistic([Distance], [-59.7559, 6.02588], P1),
                P2 is 1-P1
            ;   kind(Occluded):t+1 ~= skin
            ->  % n = 0, too few groundings for a model of its own: the parent's model, logistic
                logistic([Distance], [-22.555, 2.0822], P1),
                P2 is 1-P1
            ;   \+ kind(Occluded):t+1 ~= _
            ->  % n = 0, too few groundings for a model of its own: the parent's model, logistic
                logistic([Distance], [-22.555, 2.0822], P1),
                P2 is 1-P1
            )
        ;   \+ kind(Occluder):t+1 ~= _
        ->  % n = 0, too few groundings for a model of its own: the parent's model, logistic
            logistic([Distance], [-47.5176, 1.81678], P1),
            P2 is 1-P1
        )
    ;   % n = 0, too few groundings for a model of its own: the parent's model, finite
        P1 = 0.607982,
        P2 = 0.392018
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

% released(Held):t+1: 3 clauses, 982 groundings, training log-likelihood -33.9081 (mean -0.0345296 per grounding), 6 parameters.
released(Held):t+1 ~ finite([P1:true, P2:false]) :=
    carried(Held):t+1,
    (   height(Held):t+1 ~= Height
    ->  (   highest(Held):t+1 ~= Highest
        ->  % n = 982, log-likelihood -33.9081, logistic
            logistic([Height, Highest], [-90.0057, 31.5224, -4.94269], P1),
            P2 is 1-P1
        ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
            logistic([Height], [-53.1562, -2.09308], P1),
            P2 is 1-P1
        )
    ;   % n = 0, too few groundings for a model of its own: the parent's model, finite
        P1 = 0.0223577,
        P2 = 0.9776423
    ).

:- include('too/too_motion.pl').
