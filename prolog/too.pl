/*  too.pl -- the theory of occlusion: which object may hide which, and where a hidden object is.

    An ordinary DDC program, filtered over time by the particle filter (prolog/ddc.pl);
    edit it freely.  It is made of six parts, each a file of its own (the five included ones
    in too/) so that the theories `anchoring learn-theory` writes share what they do not learn:

      too_base.pl       the vocabulary and the frame (what the runner asserts at every step,
                        what it reads back, how a perceived object's position is filtered and
                        weighs the particles, what the camera seeing nothing means)
      too_parameters.pl the parameters (variances, reaches, heights)
      too_affordances.pl the affordances (what can hide, be hidden, carry)
      (here)            the occlusion rules: which object hides a hidden one, how long for
      too_motion.pl     the transitive clause, the carriers' rules and the motion of hidden
                        objects
      too_release.pl    when a hand lets go of what it carries
*/

:- include('too/too_base').
:- include('too/too_parameters').
:- include('too/too_affordances').

% ------------------------------------------------------------------ occlusion
% The hand-written occlusion rules (the theories anchoring learn-theory writes have learned ones
% instead).
% A container covers an object while its centre is not lifted far above the object's (a
% carrier holds what it holds: the carriers' rules below).
covers(O, A):t+1 :=
    category(O, C), \+ carrier(C), A \== O,
    pos(O):t+1 ~= (_, _, ZO), pos(A):t ~= (_, _, Z), cover_height(H), ZO < Z + H.

% O could hide A: O is perceived now, may occlude, covers A, and is near A's last position
% and not below it, or A was lost while the camera was blind (then every occluder on the
% table could).
occluder_candidate(A, O):t+1 :=
    hidden(A):t+1, can_be_occluded(A),
    observed(O), O \== A, can_occlude(O), covers(O, A):t+1,
    pos(A):t ~= (X, Y, Z), pos(O):t+1 ~= (XO, YO, ZO),
    (   lost_anywhere(A):t
    ->  true
    ;   occluder_reach(R), occluder_rise(H),
        D is sqrt((X-XO)**2 + (Y-YO)**2), D < R, Z < ZO + H
    ).

% What a particle may pick when A is hidden and under nothing:
% - A vanished just now: one of the candidates, or `behind`: A stays where it was, hidden from
%   the camera's view by something in front of it (a container carried or swapped past it,
%   two containers merged into one segment for a few frames) or missed by perception.  Without
%   that choice every particle would put a mug that vanished while another container passed
%   in front of it under that container, and the mug, seen again where it was, would be a new
%   anchor.
% - A was lost while the camera was blind: any covering occluder on the table (its old place
%   says nothing: it was moved unseen).
% - A has been hidden under nothing (behind something, or left on the table when its container
%   was lifted away, or no occluder was near when it vanished): only an occluder that is
%   lowered over it, i.e. covers it now and did not in the previous frame (a box that was
%   still too high when the mug under it vanished; a container put back over an object), or
%   one coming down onto it (below; a cup held over a ball hides it from the camera before it
%   is put down on it).  A container sliding on the table does not slide over what stands
%   there.
lowered_over(O, A):t+1 :=
    occluder_candidate(A, O):t+1, pos(A):t ~= (_, _, Z), cover_height(H),
    (   pos(O):t ~= (_, _, ZO)
    ->  ZO >= Z + H
    ;   true
    ).
% A hand that has just come to close over A (the carriers' rules below).
lowered_over(O, A):t+1 := hand_known, grasp_candidate(A, O):t+1.

% - A vanished just now as an occluder came down onto it (its centre sank by more than
%   lowering_speed since the previous frame and is within lowered_reach of A in the table
%   plane: a container put over it, a hand closing on it): under it, or `behind` with
%   behind_when_covered (the others share the rest).  An occluder passing by, or standing
%   beside A, leaves `behind` as likely as each candidate.
coming_down_on(O, A):t+1 :=
    occluder_candidate(A, O):t+1, pos(A):t ~= (X, Y, _),
    pos(O):t ~= (_, _, Z0), pos(O):t+1 ~= (XO, YO, Z1), lowering_speed(V), Z1 < Z0 - V,
    lowered_reach(R), D is sqrt((X-XO)**2 + (Y-YO)**2), D < R.

% Each particle picks among the choices (the paper's sample_occluder, plus `behind`),
% uniformly but for an occluder coming down onto A.  (In these bodies and in pos/1's, the goals every particle agrees on, such as
% seen(A):t, come before those a particle holds on its own, such as occluded_by(A, _):t:
% the same answers, fewer proofs per particle.)
pick_occluder(A):t+1 ~ uniform(Os) :=
    hidden(A):t+1, lost_anywhere(A):t, \+ occluded_by(A, _):t,
    findall_forward(O, occluder_candidate(A, O):t+1, Os0), sort(Os0, Os), Os \== [].
pick_occluder(A):t+1 ~ finite(Ds) :=
    hidden(A):t+1, seen(A):t, \+ occluded_by(A, _):t,
    findall_forward(O, coming_down_on(O, A):t+1, Os0), sort(Os0, Os1), Os1 \== [],
    behind_or_under(Os1, Ds).
pick_occluder(A):t+1 ~ uniform(Os) :=
    hidden(A):t+1, seen(A):t, \+ occluded_by(A, _):t, \+ coming_down_on(_, A):t+1,
    findall_forward(O, occluder_candidate(A, O):t+1, Os0), sort(Os0, Os1), Os1 \== [],
    Os = [behind | Os1].
pick_occluder(A):t+1 ~ uniform(Os) :=
    hidden(A):t+1, \+ seen(A):t, \+ lost_anywhere(A):t, \+ occluded_by(A, _):t,
    findall_forward(O, lowered_over(O, A):t+1, Os0), sort(Os0, Os), Os \== [].
pick_occluder(A):t+1 ~ finite(Ds) :=
    hidden(A):t+1, \+ seen(A):t, \+ lost_anywhere(A):t, \+ occluded_by(A, _):t,
    \+ lowered_over(_, A):t+1,
    findall_forward(O, coming_down_on(O, A):t+1, Os0), sort(Os0, Os), Os \== [],
    behind_or_under(Os, Ds).

occluded_by(A, O):t+1 := hidden(A):t+1, pick_occluder(A):t+1 ~= O, O \== behind.
% The occlusion lasts while the object is hidden and its occluder is perceived and still
% covers it.
occluded_by(A, O):t+1 := occluded_by(A, O):t, hidden(A):t+1, observed(O), covers(O, A):t+1.

% The choices of pick_occluder/1 when occluders Os come down onto the object: `behind` with
% behind_when_covered, each of Os with an equal share of the rest.
behind_or_under(Os, [W:behind | Ws]) :-
    behind_when_covered(W), length(Os, K), WO is (1 - W) / K,
    findall(WO:O, member(O, Os), Ws).

:- include('too/too_motion').
:- include('too/too_release').
