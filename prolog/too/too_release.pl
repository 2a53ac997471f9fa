/*  too_release.pl -- when a hand lets go of what it carries, written by hand.

    Included by too.pl after too_motion.pl (whose carriers' rules hold an object until
    released(A):t+1 ~= true).  A learned theory has in its place a tree the structure learner
    learned from the carries `anchoring collect` keeps (python/probanchor/learning/
    release_data.py), over the same state: how high the object is above where it stood
    (rest_z/1) and how high it has been since it was taken.
*/

% A has been carried up (the hand rising with it, lift_margin above where it stood) since it
% was taken ...
raised(A):t+1 ~ val(true) :=
    object(O), is_carrier(O), occluded_by(A, O):t+1,
    (   raised(A):t ~= true
    ->  true
    ;   pos(O):t ~= (_, _, ZO0), pos(O):t+1 ~= (_, _, ZO1), ZO1 > ZO0,
        pos(A):t+1 ~= (_, _, Z), rest_z(A):t+1 ~= R, lift_margin(M), Z > R + M
    ).
% ... and carried back down to within release_margin of that height: put down.  The hand lets
% it go with probability release_p per frame there (it stays where it is; the hand leaves).
released(A):t+1 ~ finite([P:true, Q:false]) :=
    object(O), is_carrier(O), occluded_by(A, O):t, observed(O), hidden(A):t+1,
    raised(A):t ~= true, pos(A):t ~= (_, _, Z), rest_z(A):t ~= R, release_margin(M),
    Z =< R + M, release_p(P), Q is 1 - P.
