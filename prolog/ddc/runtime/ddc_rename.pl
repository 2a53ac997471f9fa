/*  ddc_rename.pl -- renaming constants in the values a particle holds.

    Part of the DDC system (ddc.pl is the module users load).  The filter
    API's filter_rename/3 (ddc_filter.pl) renames constants in chosen
    particles; each engine renames its own stores (ddc_particles.pl) or
    columns (ddc_filter_batched.pl, ddc_batch_tables.pl) with the term
    renamings of this module.
*/

:- module(ddc_rename,
          [ renaming_moves/2,           % +Pairs, -Moves
            rename_term/3,              % +Moves, +Term0, -Term
            rename_arguments/3          % +Moves, +Term0, -Term
          ]).

:- use_module(library(apply)).
:- use_module(library(terms), [mapsubterms/3]).

/** <module> Renaming constants in terms

A renaming is a list of Old-New atom pairs that is a permutation of a
set of atoms (checked by filter_rename/3).  Its moves are the pairs with
Old \== New; a term in which no Old of a move occurs is left as it is
(the same term, not a copy).

Constants are atoms in argument positions: the name of a compound term
(a random variable's or a predicate's name, a value's functor) is never
renamed.  A value is renamed throughout (an atom value itself, and every
atom inside it); a key (a random variable such as pos(mug_1), a derived
atom such as occluded_by(ball_1, mug_1)) has its arguments renamed, its
name kept.
*/

%!  renaming_moves(+Pairs:list(pair), -Moves:list(pair)) is det.
%
%   Moves: the pairs of Pairs that change a name (Old \== New).
renaming_moves(Pairs, Moves) :-
    exclude(identity_pair, Pairs, Moves).

identity_pair(Old-New) :-
    Old == New.

%!  rename_term(+Moves:list(pair), +Term0, -Term) is det.
%
%   Term is Term0 with every atom that is the Old of a move (itself, or at
%   any depth as an argument) replaced by its New.
rename_term([], T, T) :- !.
rename_term(Moves, T0, T) :-
    mapsubterms(renamed_atom(Moves), T0, T).

renamed_atom(Moves, A, B) :-
    atom(A),
    memberchk(A-B, Moves).

%!  rename_arguments(+Moves:list(pair), +Term0, -Term) is det.
%
%   Term is Term0 with its arguments renamed by rename_term/3, its name
%   kept (an atom Term0 is left as it is).
rename_arguments(Moves, T0, T) :-
    (   Moves \== [], compound(T0)
    ->  compound_name_arguments(T0, Name, Args0),
        maplist(rename_term(Moves), Args0, Args),
        compound_name_arguments(T, Name, Args)
    ;   T = T0
    ).
