/*  too_learned_glue.pl -- how a learned theory of occlusion uses its learned trees.

    Hand-written, and included by the theories `anchoring learn-theory` writes (after their
    learned affordances and parameters, before their learned trees): which pairs the learned
    occluder(A, O):t+1 is drawn for, how a particle picks among the candidates it gives, and
    how an occlusion goes on; for which objects the learned released(A):t+1 is drawn, and the
    state it reads.  Reads onset_reach/1 and onset_reach/2 (the reach of all onsets and of
    the kinds with onsets enough for their own), fitted from the data and written into the
    theory (python/probanchor/learning/occlusion_reach.py), and the affordances can_occlude/1
    and can_be_occluded/1, learned too.
*/

% ------------------------------------------------------------------ learned occlusion rules
% How the learned occluder/2 (below) is used, as the paper's theory uses its occluder rule
% (section 2.3): the pairs it is about are a hidden A and a perceived O (the data's examples)
% that the learned affordances above allow (a ball hides nothing, a hand is never hidden; the
% tree gives a ball as occluder a probability of about 1e-4 per frame, and one particle of a
% hidden ball under the other, identical ball is enough for the matching to swap them);
% of those, only the pairs that can matter: O hid A at t (the occlusion may go on), A was lost
% while the camera saw nothing (any occluder may have it), or O is within the onset reach of
% its kind of where A was (fitted from the data: twice the distance within which 90 % of the
% onsets by that kind were, or by any kind for a kind with few onsets); beyond it the learned
% tree gives an onset a negligible probability (the tree is learned from the pairs asked about
% here), and a draw for every pair in every particle would cost more than the rest of the
% theory.
% O is a candidate occluder of the hidden A when the particle
% draws occluder(A, O):t+1 ~= true; the particle picks one candidate uniformly; when none is
% drawn A is under nothing (behind something, or left where it was), so the share of the
% vanishings under nothing is the tree's own (the data's vanishings with no occluder are among
% its examples; too.pl adds a `behind` choice by hand).  A carrier's grip over A
% (too/too_motion.pl's grasp_candidate/2) is no draw of the tree: when A has just vanished
% with a carrier among the candidates, `behind` is one more choice (A stays where it was,
% hidden from view: the hand may pass over it; as in too.pl).  The occlusion goes on while
% O is perceived and the particle draws occluder(A, O):t+1 ~= true.
pair(A, O):t+1 :=
    hidden(A):t+1, observed(O), O \== A, can_be_occluded(A), can_occlude(O),
    (   occluded_by(A, O):t
    ->  true
    ;   lost_anywhere(A):t
    ->  true
    ;   pos(O):t+1 ~= (XO, YO, _), pos(A):t ~= (X, Y, _), reach_of(O, R),
        (X-XO)**2 + (Y-YO)**2 < R*R
    ).
:- dynamic(onset_reach/2).
reach_of(O, R) := category(O, C), onset_reach(C, R).
reach_of(O, R) := category(O, C), \+ onset_reach(C, _), onset_reach(R).
occluder_candidate(A, O):t+1 :=
    pair(A, O):t+1, \+ occluded_by(A, O):t, occluder(A, O):t+1 ~= true.
pick_occluder(A):t+1 ~ uniform(Os) :=
    hidden(A):t+1, \+ occluded_by(A, _):t,
    findall_forward(O, occluder_candidate(A, O):t+1, Os0), sort(Os0, Os1), Os1 \== [],
    (   seen(A):t, member(O, Os1), is_carrier(O)
    ->  Os = [behind | Os1]
    ;   Os = Os1
    ).
occluded_by(A, O):t+1 := hidden(A):t+1, pick_occluder(A):t+1 ~= O, O \== behind.
occluded_by(A, O):t+1 :=
    occluded_by(A, O):t, seen(O):t, pair(A, O):t+1, occluder(A, O):t+1 ~= true.
% An occluder out of view at t (the camera saw nothing, or it was hidden itself) that is
% perceived again still hides what it hid (as the transitive clause kept it while unseen): the
% data have no occluder moved while out of view, so the tree's distance from where A was would
% end the occlusion wherever the occluder was taken unseen (two look-alike containers swapped
% while the camera was covered); from the next frame on, the tree decides again.
occluded_by(A, O):t+1 :=
    occluded_by(A, O):t, hidden(A):t+1, observed(O), \+ seen(O):t.

% ------------------------------------------------------------------ learned release
% How the learned released/1 (the second tree below) is used: it is drawn for what a carrier
% holds (carried/1, the data's examples: A under a carrier at t that is perceived at t+1, A
% still hidden), and too/too_motion.pl's carriers' rules hold A until a particle draws
% released(A):t+1 ~= true.  The tree reads how high A is above where it stood (rest_z/1,
% too_motion.pl) and top/1: the highest A has been above it since the hand took it.
carried(A):t+1 :=
    object(O), is_carrier(O), occluded_by(A, O):t, observed(O), hidden(A):t+1.
top(A):t+1 ~ val(H) :=
    object(O), is_carrier(O), occluded_by(A, O):t+1, rest_z(A):t+1 ~= R,
    pos(A):t+1 ~= (_, _, Z),
    (   top(A):t ~= H0
    ->  H is max(H0, Z - R)
    ;   H is Z - R
    ).
