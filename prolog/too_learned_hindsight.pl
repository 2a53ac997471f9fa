/*  too_learned_hindsight.pl -- the theory of occlusion with rules learned from experience.

    Written by `anchoring learn-theory`: a tree learned (ddc learn) from
    data_hindsight.pl: 13349 groundings of occluder(A, O):t+1,
    87 clauses, training log-likelihood -3011.57;
    and one for released(A):t+1 from 974 frames a hand held an object
    (3 clauses, training log-likelihood -35.2656);
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
obs_var(3.734e-06).  % the measurement noise of a perceived position (m², per axis); 90,941 samples
motion_var(3.394e-05).  % how far a perceived object moves in a frame (m², per axis); 121,610 samples
reappear_var(0.001287).  % where a hidden object is seen again, around its belief (m²); 1,351 samples
lost_var(0.07289).  % the same for an object lost while the camera saw nothing (m²); 8,202 samples
follow_keep(0.999).  % the fraction of its offset from its occluder a hidden object keeps; 18 samples
follow_var(1.15e-07).  % the jitter of that offset per frame (m²); 18 samples
coast_keep(0.9092).  % the fraction of its velocity a hidden object under nothing keeps; 34 samples
wander_var(0.0002792).  % how far such an object may move besides (m²); 34 samples
grip_reach(0.06474).  % how far (table plane) a hand's grip may be from what it takes (m); 19 samples
grip_height(0.1257).  % how far above its top (m); 19 samples
occluder_rise(0.002776).  % how far below its centre (m); 19 samples
grip_drop(0.04105).  % how far what a hand holds is below its grip (m); 19 samples
grip_rise(0.001085).  % how far a hand's grip rises in a frame when it lifts (m); 261 samples
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
hides(ball, 0.0002129).  % 9,567
hides(bottle, 0.0001633).  % 6,120
hides(bowl, 0.09386).  % 6,710
hides(box, 0.2302).  % 21,774
hides(can, 0.000235).  % 4,253
hides(cup, 0.04766).  % 15,818
hides(mug, 0.06659).  % 13,528
hides(skin, 0.3197).  % 3,286
hidden_share(ball, 0.1732).  % 29,024
hidden_share(bottle, 0.08805).  % 1,387
hidden_share(bowl, 0.00742).  % 7,815
hidden_share(box, 0.02845).  % 6,853
hidden_share(can, 0.1498).  % 3,455
hidden_share(cup, 0.1293).  % 16,813
hidden_share(mug, 0.02036).  % 12,574
hidden_share(skin, 0.0003188).  % 3,135
carries(bowl, 0.6667).  % 1
carries(box, 0.8333).  % 4
carries(skin, 0.9981).  % 532
carrier(skin).
can_occlude(O) := category(O, C), hides(C, P), P >= 0.01, \+ is_carrier(O).
is_carrier(O) := category(O, C), carrier(C).
hand_known := object(O), is_carrier(O).
can_be_occluded(A) := category(A, C), hidden_share(C, P), P >= 0.01.

:- include('too/too_learned_glue.pl').
% The onset reach (m): 90% of the 32 onsets in the data were within 0.04984 m; times 2.0.
onset_reach(0.0997).
% The reach of the kinds with onsets enough for one of their own.
onset_reach(box, 0.1014).  % 16 onsets, 90% within 0.05069 m

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
moved(O):t+1 ~ val(M) :=
    pos(O):t ~= (X0, Y0, Z0),
    pos(O):t+1 ~= (X1, Y1, Z1),
    M is sqrt((X1-X0)**2+(Y1-Y0)**2+(Z1-Z0)**2).
kind(A):t+1 ~ val(C) :=
    category(A, C).

% occluder(Occluded, Occluder):t+1: 87 clauses, 13349 groundings, training log-likelihood -3011.57 (mean -0.111643 per grounding), 105 parameters.
occluder(Occluded, Occluder):t+1 ~ finite([P1:true, P2:false]) :=
    pair(Occluded, Occluder):t+1,
    (   distance(Occluded, Occluder):t+1 ~= Distance
    ->  (   kind(Occluder):t+1 ~= ball
        ->  % n = 208 (weight 594), log-likelihood -7.91873, finite
            P1 = 0.00341772,
            P2 = 0.99658228
        ;   kind(Occluder):t+1 ~= bottle
        ->  % n = 72 (weight 300), log-likelihood -0.995026, finite
            P1 = 0.00331126,
            P2 = 0.99668874
        ;   kind(Occluder):t+1 ~= bowl
        ->  (   kind(Occluded):t+1 ~= ball
            ->  (   lost_anywhere(Occluded):t
                ->  % n = 178 (weight 578), log-likelihood -7.66297, finite
                    P1 = 0.00344828,
                    P2 = 0.99655172
                ;   (   rise(Occluded, Occluder):t+1 ~= Rise
                    ->  (   Rise < 0.0
                        ->  % n = 98 (weight 286), log-likelihood -6.95588, finite
                            P1 = 0.99305556,
                            P2 = 0.00694444
                        ;   Rise < 0.1
                        ->  (   moved(Occluder):t+1 ~= Moved
                            ->  (   Moved < 0.004
                                ->  % n = 252 (weight 576), log-likelihood -164.32, logistic
                                    logistic([Distance], [-440.565, 7.0907], P1),
                                    P2 is 1-P1
                                ;   (   occluded_by(Occluded, Occluder):t
                                    ->  % n = 54 (weight 66), log-likelihood -0.977796, finite
                                        P1 = 0.9852941,
                                        P2 = 0.0147059
                                    ;   % n = 138 (weight 170), log-likelihood -78.9554, logistic
                                        logistic([Distance], [-84.6486, 1.1565], P1),
                                        P2 is 1-P1
                                    )
                                )
                            ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                                logistic([Distance], [-308.257, 4.9793], P1),
                                P2 is 1-P1
                            )
                        ;   (   occluded_by(Occluded, Occluder):t
                            ->  % n = 11 (weight 15), log-likelihood -0.909369, finite
                                P1 = 0.9411765,
                                P2 = 0.0588235
                            ;   % n = 47 (weight 51), log-likelihood -23.7792, logistic
                                logistic([Distance], [-57.9235, 0.67485], P1),
                                P2 is 1-P1
                            )
                        )
                    ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                        logistic([Distance], [-182.587, 3.37517], P1),
                        P2 is 1-P1
                    )
                )
            ;   kind(Occluded):t+1 ~= bottle
            ->  % n = 14, log-likelihood -0.903539, finite
                P1 = 0.0625,
                P2 = 0.9375
            ;   kind(Occluded):t+1 ~= bowl
            ->  % n = 162 (weight 326), log-likelihood -7.08764, finite
                P1 = 0.00609756,
                P2 = 0.99390244
            ;   kind(Occluded):t+1 ~= box
            ->  % n = 110 (weight 286), log-likelihood -0.994784, finite
                P1 = 0.00347222,
                P2 = 0.99652778
            ;   kind(Occluded):t+1 ~= can
            ->  % n = 4, too few groundings for a model of its own: the parent's model, log-likelihood -0.000705675, logistic
                logistic([Distance], [-141.103, 2.18764], P1),
                P2 is 1-P1
            ;   kind(Occluded):t+1 ~= cup
            ->  (   moved(Occluder):t+1 ~= Moved3
                ->  (   Moved3 < 0.004
                    ->  % n = 64 (weight 188), log-likelihood -6.0567, logistic
                        logistic([Distance], [-430.401, 13.8379], P1),
                        P2 is 1-P1
                    ;   % n = 72 (weight 108), log-likelihood -15.1539, logistic
                        logistic([Distance], [-148.213, 5.65444], P1),
                        P2 is 1-P1
                    )
                ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                    logistic([Distance], [-264.701, 8.8998], P1),
                    P2 is 1-P1
                )
            ;   kind(Occluded):t+1 ~= mug
            ->  % n = 69 (weight 157), log-likelihood -0.99054, finite
                P1 = 0.00628931,
                P2 = 0.99371069
            ;   kind(Occluded):t+1 ~= skin
            ->  % n = 0, too few groundings for a model of its own: the parent's model, logistic
                logistic([Distance], [-141.103, 2.18764], P1),
                P2 is 1-P1
            ;   \+ kind(Occluded):t+1 ~= _
            ->  % n = 0, too few groundings for a model of its own: the parent's model, logistic
                logistic([Distance], [-141.103, 2.18764], P1),
                P2 is 1-P1
            )
        ;   kind(Occluder):t+1 ~= box
        ->  (   kind(Occluded):t+1 ~= ball
            ->  (   occluded_by(Occluded, Occluder):t
                ->  % n = 754 (weight 2590), log-likelihood -0.999421, finite
                    P1 = 0.999614198,
                    P2 = 0.000385802
                ;   (   lost_anywhere(Occluded):t
                    ->  (   moved(Occluder):t+1 ~= Moved6
                        ->  (   Moved6 < 0.004
                            ->  % n = 148 (weight 740), log-likelihood -0.997977, finite
                                P1 = 0.00134771,
                                P2 = 0.99865229
                            ;   % n = 64 (weight 84), log-likelihood -13.062, finite
                                P1 = 0.0465116,
                                P2 = 0.9534884
                            )
                        ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                            logistic([Distance], [-16.9761, -3.38524], P1),
                            P2 is 1-P1
                        )
                    ;   % n = 2381 (weight 2893), log-likelihood -1368.29, logistic
                        logistic([Distance], [-46.4144, 1.98698], P1),
                        P2 is 1-P1
                    )
                )
            ;   kind(Occluded):t+1 ~= bottle
            ->  % n = 6 (weight 10), log-likelihood -0.870114, finite
                P1 = 0.0833333,
                P2 = 0.9166667
            ;   kind(Occluded):t+1 ~= bowl
            ->  % n = 81 (weight 189), log-likelihood -0.992128, finite
                P1 = 0.0052356,
                P2 = 0.9947644
            ;   kind(Occluded):t+1 ~= box
            ->  % n = 74 (weight 262), log-likelihood -0.994309, finite
                P1 = 0.00378788,
                P2 = 0.99621212
            ;   kind(Occluded):t+1 ~= can
            ->  (   rise(Occluded, Occluder):t+1 ~= Rise4
                ->  (   Rise4 < 0.0
                    ->  % n = 31 (weight 111), log-likelihood -10.1905, finite
                        P1 = 0.0265487,
                        P2 = 0.9734513
                    ;   Rise4 < 0.1
                    ->  (   occluded_by(Occluded, Occluder):t
                        ->  % n = 141 (weight 473), log-likelihood -0.996839, finite
                            P1 = 0.99789474,
                            P2 = 0.00210526
                        ;   % n = 491 (weight 523), log-likelihood -188.372, finite
                            P1 = 0.881905,
                            P2 = 0.118095
                        )
                    ;   % n = 21 (weight 29), log-likelihood -0.950905, finite
                        P1 = 0.0322581,
                        P2 = 0.9677419
                    )
                ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                    logistic([Distance], [-28.9048, 1.76898], P1),
                    P2 is 1-P1
                )
            ;   kind(Occluded):t+1 ~= cup
            ->  (   moved(Occluder):t+1 ~= Moved9
                ->  (   Moved9 < 0.004
                    ->  % n = 1238 (weight 2770), log-likelihood -11.199, logistic
                        logistic([Distance], [-147.328, 11.6488], P1),
                        P2 is 1-P1
                    ;   % n = 150 (weight 158), log-likelihood -18.9552, logistic
                        logistic([Distance], [-147.255, 7.54368], P1),
                        P2 is 1-P1
                    )
                ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
                    logistic([Distance], [-217.929, 13.5149], P1),
                    P2 is 1-P1
                )
            ;   kind(Occluded):t+1 ~= mug
            ->  % n = 75 (weight 151), log-likelihood -0.990167, finite
                P1 = 0.00653595,
                P2 = 0.99346405
            ;   kind(Occluded):t+1 ~= skin
            ->  % n = 114 (weight 262), log-likelihood -0.994309, finite
                P1 = 0.00378788,
                P2 = 0.99621212
            ;   \+ kind(Occluded):t+1 ~= _
            ->  % n = 0, too few groundings for a model of its own: the parent's model, logistic
                logistic([Distance], [-57.6827, 2.90155], P1),
                P2 is 1-P1
            )
        ;   kind(Occluder):t+1 ~= can
        ->  % n = 223 (weight 647), log-likelihood -0.997687, finite
            P1 = 0.00154083,
            P2 = 0.99845917
        ;   kind(Occluder):t+1 ~= cup
        ->  (   kind(Occluded):t+1 ~= ball
            ->  (   occluded_by(Occluded, Occluder):t
                ->  % n = 234 (weight 746), log-likelihood -0.997993, finite
                    P1 = 0.9986631,
                    P2 = 0.0013369
                ;   (   lost_anywhere(Occluded):t
                    ->  (   seen(Occluder):t
                        ->  % n = 182 (weight 822), log-likelihood -0.998179, finite
                            P1 = 0.00121359,
                            P2 = 0.99878641
                        ;   % n = 11 (weight 19), log-likelihood -8.35563, finite
                            P1 = 0.190476,
                            P2 = 0.809524
                        )
                    ;   % n = 683 (weight 783), log-likelihood -365.341, logistic
                        logistic([Distance], [-40.1551, 1.82078], P1),
                        P2 is 1-P1
                    )
                )
            ;   kind(Occluded):t+1 ~= bottle
            ->  % n = 5, too few groundings for a model of its own: the parent's model, log-likelihood -3.69499e-06, logistic
                logistic([Distance], [-179.824, 1.35166], P1),
                P2 is 1-P1
            ;   kind(Occluded):t+1 ~= bowl
            ->  % n = 5 (weight 17), log-likelihood -0.919143, finite
                P1 = 0.0526316,
                P2 = 0.9473684
            ;   kind(Occluded):t+1 ~= box
            ->  % n = 29 (weight 141), log-likelihood -0.989478, finite
                P1 = 0.00699301,
                P2 = 0.99300699
            ;   kind(Occluded):t+1 ~= can
            ->  % n = 1, too few groundings for a model of its own: the parent's model, log-likelihood -2.25067e-07, logistic
                logistic([Distance], [-179.824, 1.35166], P1),
                P2 is 1-P1
            ;   kind(Occluded):t+1 ~= cup
            ->  % n = 630 (weight 1558), log-likelihood -0.999038, finite
                P1 = 0.000641026,
                P2 = 0.999358974
            ;   kind(Occluded):t+1 ~= mug
            ->  % n = 262 (weight 882), log-likelihood -0.998302, finite
                P1 = 0.00113122,
                P2 = 0.99886878
            ;   kind(Occluded):t+1 ~= skin
            ->  % n = 0, too few groundings for a model of its own: the parent's model, logistic
                logistic([Distance], [-179.824, 1.35166], P1),
                P2 is 1-P1
            ;   \+ kind(Occluded):t+1 ~= _
            ->  % n = 0, too few groundings for a model of its own: the parent's model, logistic
                logistic([Distance], [-179.824, 1.35166], P1),
                P2 is 1-P1
            )
        ;   kind(Occluder):t+1 ~= mug
        ->  (   kind(Occluded):t+1 ~= ball
            ->  (   occluded_by(Occluded, Occluder):t
                ->  % n = 242 (weight 890), log-likelihood -0.998318, finite
                    P1 = 0.99887892,
                    P2 = 0.00112108
                ;   % n = 1413 (weight 2353), log-likelihood -240.874, logistic
                    logistic([Distance], [-101.302, 4.84209], P1),
                    P2 is 1-P1
                )
            ;   kind(Occluded):t+1 ~= bottle
            ->  % n = 1, too few groundings for a model of its own: the parent's model, log-likelihood -1.18532, logistic
                logistic([Distance], [-93.8449, 2.29868], P1),
                P2 is 1-P1
            ;   kind(Occluded):t+1 ~= bowl
            ->  % n = 9 (weight 17), log-likelihood -0.919143, finite
                P1 = 0.0526316,
                P2 = 0.9473684
            ;   kind(Occluded):t+1 ~= box
            ->  % n = 8 (weight 12), log-likelihood -0.889296, finite
                P1 = 0.0714286,
                P2 = 0.9285714
            ;   kind(Occluded):t+1 ~= can
            ->  % n = 1, too few groundings for a model of its own: the parent's model, log-likelihood -0.000915401, logistic
                logistic([Distance], [-93.8449, 2.29868], P1),
                P2 is 1-P1
            ;   kind(Occluded):t+1 ~= cup
            ->  (   moved(Occluder):t+1 ~= Moved12
                ->  (   Moved12 < 0.004
                    ->  % n = 12 (weight 20), log-likelihood -0.9304, finite
                        P1 = 0.0454545,
                        P2 = 0.9545455
                    ;   % n = 16, log-likelihood -11.0904, finite
                        P1 = 0.5,
                        P2 = 0.5
                    )
                ;   % n = 0, too few groundings for a model of its own: the parent's model, finite
                    P1 = 0.236842,
                    P2 = 0.763158
                )
            ;   kind(Occluded):t+1 ~= mug
            ->  % n = 220 (weight 792), log-likelihood -0.99811, finite
                P1 = 0.00125945,
                P2 = 0.99874055
            ;   kind(Occluded):t+1 ~= skin
            ->  % n = 30 (weight 150), log-likelihood -0.990103, finite
                P1 = 0.00657895,
                P2 = 0.99342105
            ;   \+ kind(Occluded):t+1 ~= _
            ->  % n = 0, too few groundings for a model of its own: the parent's model, logistic
                logistic([Distance], [-93.8449, 2.29868], P1),
                P2 is 1-P1
            )
        ;   kind(Occluder):t+1 ~= skin
        ->  (   occluded_by(Occluded, Occluder):t
            ->  (   kind(Occluded):t+1 ~= ball
                ->  % n = 148 (weight 184), log-likelihood -0.991916, finite
                    P1 = 0.99462366,
                    P2 = 0.00537634
                ;   kind(Occluded):t+1 ~= bottle
                ->  % n = 150 (weight 117.78), log-likelihood -47.6926, finite
                    P1 = 0.854087,
                    P2 = 0.145913
                ;   kind(Occluded):t+1 ~= bowl
                ->  % n = 39 (weight 55), log-likelihood -0.973477, finite
                    P1 = 0.9824561,
                    P2 = 0.0175439
                ;   kind(Occluded):t+1 ~= box
                ->  % n = 143 (weight 191), log-likelihood -0.99221, finite
                    P1 = 0.99481865,
                    P2 = 0.00518135
                ;   kind(Occluded):t+1 ~= can
                ->  % n = 32 (weight 40), log-likelihood -0.963902, finite
                    P1 = 0.9761905,
                    P2 = 0.0238095
                ;   kind(Occluded):t+1 ~= cup
                ->  % n = 146 (weight 190), log-likelihood -0.992169, finite
                    P1 = 0.99479167,
                    P2 = 0.00520833
                ;   kind(Occluded):t+1 ~= mug
                ->  % n = 181 (weight 249), log-likelihood -0.994013, finite
                    P1 = 0.99601594,
                    P2 = 0.00398406
                ;   kind(Occluded):t+1 ~= skin
                ->  % n = 0, too few groundings for a model of its own: the parent's model, finite
                    P1 = 0.9830115,
                    P2 = 0.0169885
                ;   \+ kind(Occluded):t+1 ~= _
                ->  % n = 0, too few groundings for a model of its own: the parent's model, finite
                    P1 = 0.9830115,
                    P2 = 0.0169885
                )
            ;   (   kind(Occluded):t+1 ~= ball
                ->  (   lost_anywhere(Occluded):t
                    ->  % n = 150 (weight 190), log-likelihood -0.992169, finite
                        P1 = 0.00520833,
                        P2 = 0.99479167
                    ;   % n = 151, log-likelihood -40.5713, logistic
                        logistic([Distance], [-60.8424, 3.85481], P1),
                        P2 is 1-P1
                    )
                ;   kind(Occluded):t+1 ~= bottle
                ->  % n = 147 (weight 103.22), log-likelihood -48.9711, finite
                    P1 = 0.81202,
                    P2 = 0.18798
                ;   kind(Occluded):t+1 ~= bowl
                ->  % n = 55 (weight 59), log-likelihood -22.7691, logistic
                    logistic([Distance], [-67.7144, 4.15318], P1),
                    P2 is 1-P1
                ;   kind(Occluded):t+1 ~= box
                ->  % n = 85, log-likelihood -8.63546, logistic
                    logistic([Distance], [-67.8609, 5.69811], P1),
                    P2 is 1-P1
                ;   kind(Occluded):t+1 ~= can
                ->  (   lost_anywhere(Occluded):t
                    ->  % n = 52 (weight 76), log-likelihood -0.980659, finite
                        P1 = 0.0128205,
                        P2 = 0.9871795
                    ;   % n = 41, log-likelihood -12.0217, logistic
                        logistic([Distance], [-99.7705, 3.73799], P1),
                        P2 is 1-P1
                    )
                ;   kind(Occluded):t+1 ~= cup
                ->  % n = 188 (weight 216), log-likelihood -143.254, logistic
                    logistic([Distance], [19.9984, -0.553723], P1),
                    P2 is 1-P1
                ;   kind(Occluded):t+1 ~= mug
                ->  % n = 178 (weight 190), log-likelihood -97.7893, finite
                    P1 = 0.786458,
                    P2 = 0.213542
                ;   kind(Occluded):t+1 ~= skin
                ->  % n = 0, too few groundings for a model of its own: the parent's model, logistic
                    logistic([Distance], [-23.8632, 1.61169], P1),
                    P2 is 1-P1
                ;   \+ kind(Occluded):t+1 ~= _
                ->  % n = 0, too few groundings for a model of its own: the parent's model, logistic
                    logistic([Distance], [-23.8632, 1.61169], P1),
                    P2 is 1-P1
                )
            )
        ;   \+ kind(Occluder):t+1 ~= _
        ->  % n = 0, too few groundings for a model of its own: the parent's model, logistic
            logistic([Distance], [-60.9297, 1.89303], P1),
            P2 is 1-P1
        )
    ;   % n = 0, too few groundings for a model of its own: the parent's model, finite
        P1 = 0.535967,
        P2 = 0.464033
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

% released(Held):t+1: 3 clauses, 974 groundings, training log-likelihood -35.2656 (mean -0.036207 per grounding), 6 parameters.
released(Held):t+1 ~ finite([P1:true, P2:false]) :=
    carried(Held):t+1,
    (   height(Held):t+1 ~= Height
    ->  (   highest(Held):t+1 ~= Highest
        ->  % n = 974, log-likelihood -35.2656, logistic
            logistic([Height, Highest], [-79.1454, 28.8099, -4.89208], P1),
            P2 is 1-P1
        ;   % n = 0, too few groundings for a model of its own: the parent's model, logistic
            logistic([Height], [-50.4278, -2.10792], P1),
            P2 is 1-P1
        )
    ;   % n = 0, too few groundings for a model of its own: the parent's model, finite
        P1 = 0.0204918,
        P2 = 0.9795082
    ).

:- include('too/too_motion.pl').
