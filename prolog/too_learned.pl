/*  too_learned.pl -- the theory of occlusion with rules learned from experience.

    Written by `anchoring learn-theory`: the hand-written occlusion rules of
    too.pl are replaced by a tree learned (ddc learn) from data_truth.pl:
    78093 groundings of occluder(A, O):t+1, 85 clauses,
    training log-likelihood -24831.9; search seed 0.
    Command: anchoring learn-theory out/learn/data_truth.pl --seed 0 --out prolog/too_learned.pl --plots docs/images
    The hand-written parts are included from prolog/ (too_base.pl, too_knowledge.pl,
    too_motion.pl): regenerate this file rather than edit it; edit those for the rest.
*/

:- include('too_base.pl').
:- include('too_knowledge.pl').

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

:- include('too_motion.pl').
