/*  ddc_batch_tables.pl -- the batched filter's tables of columns.

    Part of the batched particle filter (ddc_batch.pl, the API): the
    particles' values of a random variable at a time are one column term
    c(V1, ..., VN); this module holds the columns of a time in a table,
    keyed by the variable, with what is known of each column (its entry),
    the tables of the two times a filter keeps, and the resampling of
    tables.
*/

:- module(ddc_batch_tables,
          [ table_new/1,                % -Table
            table_get/3,                % +Table, +Key, -Entry
            table_put/3,                % +Table, +Key, +Entry
            table_match/3,              % +Table, ?Key, -Entry
            new_column/3,               % +N, +Value, -Column (ddc_batch_col.pl's col_new/3)
            uncomputed/3,               % +Ps, +Column, -Missing (col_uncomputed/3)
            defined_at/3,               % +Ps, +Column, -Defined (col_defined_at/3)
            settle/1,                   % !Entry
            entry_tuple_arity/2,        % !Entry, -Arity
            tuple_shape/2,              % +K, -Shape
            real_table/2,               % +Table0, -Table
            resample_tables/3,          % +Sources, +Pairs, -Table
            rename_table/5              % +Table0, +Moves, +Ps, +N, -Table
          ]).

:- use_module(library(apply)).
:- use_module(library(lists)).
:- use_module('../lang/ddc_records').
:- use_module(ddc_batch_col).
:- reexport(ddc_batch_col, [col_new/3 as new_column, col_uncomputed/3 as uncomputed,
                            col_defined_at/3 as defined_at]).
:- use_module('../runtime/ddc_rename', [rename_term/3, rename_arguments/3]).

:- set_prolog_flag(optimise, true).

/** <module> Tables of columns for the batched filter

A column (ddc_batch_col.pl) holds a value per particle: '$u' where the
particle's value is not drawn yet, '$undef' where no clause applies.

A table holds the columns of one time: Key -> entry(Column, Status,
Arity), Status one of open (some particle may lack its value: '$u'),
same(V) (every particle holds V, '$undef' where no clause applied),
defined (each particle a value of its own), mixed (some undefined).  It
has a fixed number of bucket chains (1024: table_new/1); an entry is
copied once, when put, and then updated in place, so that a column taken
from the table stays the table's own.  Arity: the tuple arity of all of
a defined column's values, unknown until found (entry_tuple_arity/2), or
none.

A filter keeps the tables of two times, a tables(OlderTime, Older,
LatestTime, Latest) record: queries read both, a step writes the latest
only.  After a resampling the older table is pending(Sources, Pairs)
until a query first reads it (real_table/2).
*/

%   entry(Column, Status, Arity): a table's entry (above).
:- record_type entry(column, status, arity).

%   tables(OlderTime, Older, LatestTime, Latest): the tables of two times
%   (Older none at time 0, or in a worker's copy of a group).
:- record_type tables(older_time, older, latest_time, latest).

                 /*******************************
                 *        TABLES OF A TIME      *
                 *******************************/

%   (The buckets are a term's arguments, indexed by the key's hash: the
%   only arg/3 on a table.)

%!  table_new(-Table) is det.
table_new(T) :- functor(T, tab, 1024).

%!  table_get(+Table, +Key, -Entry) is semidet.
table_get(T, K, E) :-
    term_hash(K, H), I is H mod 1024 + 1,
    arg(I, T, L), nonvar(L), memberchk(K-E0, L), E = E0.

%!  table_put(!Table, +Key, +Entry) is det.
%
%   Adds a copy of Key-Entry to Table (a term made by unification may be
%   undone: the copy is the table's own).
table_put(T, K, E) :-
    term_hash(K, H), I is H mod 1024 + 1,
    arg(I, T, L),
    duplicate_term(K-E, KE),
    (   var(L) -> nb_linkarg(I, T, [KE]) ; nb_linkarg(I, T, [KE|L]) ).

%   table_link(+T, +K, +E): as table_put/3 for an entry made by construction
%   (no binding to undo): linked, not copied.
table_link(T, K, E) :-
    term_hash(K, H), I is H mod 1024 + 1,
    arg(I, T, L),
    (   var(L) -> nb_linkarg(I, T, [K-E]) ; nb_linkarg(I, T, [K-E|L]) ).

%!  table_match(+Table, ?Key, -Entry) is nondet.
table_match(T, K, E) :-
    arg(_, T, L), nonvar(L), member(K-E, L).

                 /*******************************
                 *            ENTRIES           *
                 *******************************/

%!  settle(!Entry) is det.
%
%   Entry's status once every particle has a value (unchanged, open,
%   while one lacks it).
settle(Entry) :-
    entry_column(Entry, C),
    col_status(C, S),
    (   S == open -> true
    ;   nb_set_entry_status(Entry, S)
    ).

%!  entry_tuple_arity(!Entry, -Arity) is det.
%
%   The tuple arity every value of a defined entry has, or none; found
%   once, then kept in the entry.
entry_tuple_arity(Entry, Arity) :-
    entry_arity(Entry, A0),
    (   A0 \== unknown
    ->  Arity = A0
    ;   entry_column(Entry, C),
        (   col_num_arity(C, K0)
        ->  ( K0 > 1 -> A = K0 ; A = none )
        ;   col_arg(1, C, V1),
            value_arity(V1, 1, K),
            (   K > 1, col_size(C, N), with_arity_all(N, C, K) -> A = K ; A = none )
        ),
        nb_set_entry_arity(Entry, A),
        Arity = A
    ).

with_arity_all(N, C, K) :-
    tuple_shape(K, Shape),
    forall(between(1, N, I), ( col_arg(I, C, V), subsumes_term(Shape, V) )).

value_arity(V, K0, K) :-
    (   nonvar(V), V = (_, B) -> K1 is K0+1, value_arity(B, K1, K) ; K = K0 ).

%!  tuple_shape(+K, -Shape) is det.
%
%   Shape is (_, ..., _) of K elements (the last any term).
tuple_shape(1, _) :- !.
tuple_shape(K, (_, S)) :- K1 is K-1, tuple_shape(K1, S).

                 /*******************************
                 *          RESAMPLING          *
                 *******************************/

%!  real_table(+Table0, -Table) is det.
%
%   Table0 itself, or the table a pending(Sources, Pairs) stands for,
%   resampled now.
real_table(pending(Srcs, Pairs), Tab) :- !,
    resample_tables(Srcs, Pairs, Tab).
real_table(Tab, Tab).

%!  resample_tables(+Sources:list, +Pairs:list, -Table) is det.
%
%   A table of the particles Pairs (Group-Index, 1-based) of the tables
%   Sources (one per group, each a table, pending/2 or none; a key a group
%   lacks is '$u' there: never drawn in those particles).
resample_tables(Srcs0, Pairs, New) :-
    maplist(real_table, Srcs0, Srcs),
    table_new(New),
    findall(K, ( member(Tab, Srcs), Tab \== none, table_match(Tab, K, _) ), Ks0),
    sort(Ks0, Ks),
    col_plan_size(Pairs, N),
    forall(member(K, Ks),
           (   maplist(source_entry(K), Srcs, Es),
               resampled_entry(Es, Pairs, N, E),
               table_link(New, K, E)
           )).

source_entry(K, Tab, E) :-
    (   Tab \== none, table_get(Tab, K, E0) -> E = E0 ; E = none ).

%   (A column of one value is the same after resampling: a source's of the
%   same length is shared, not copied: a complete column is never written.)
resampled_entry(Es, Pairs, N, E) :-
    (   Es = [E1|_], E1 \== none, entry_status(E1, Same), Same = same(V),
        entry_arity(E1, A),
        forall(member(E2, Es), same_entry(E2, V))
    ->  (   member(E2, Es), E2 \== none, entry_column(E2, C0), col_size(C0, N)
        ->  C1 = C0
        ;   col_new(N, V, C), duplicate_term(C, C1)
        ),
        linked_entry(C1, Same, A, E)
    ;   maplist(source_column, Es, Cs),
        col_gather(Cs, Pairs, C),
        (   forall(member(E1, Es), defined_entry(E1))
        ->  common_arity(Es, A),
            linked_entry(C, defined, A, E)
        ;   linked_entry(C, open, unknown, E0),
            duplicate_term(E0, E),
            settle(E)
        )
    ).

%   linked_entry(+Column, +Status, +Arity, -Entry): a new entry whose
%   fields are set by nb_linkarg/3 (not copied), so that it stays as made
%   when the query backtracks over its making (a field bound by its
%   accessor, arg/3, would be unbound again): for table_link/3.
linked_entry(C, S, A, E) :-
    new_entry(E),
    nb_link_entry_column(E, C),
    nb_link_entry_status(E, S),
    nb_link_entry_arity(E, A).

same_entry(E, V) :- E \== none, entry_status(E, same(V1)), V1 == V.

%   defined_entry(+E): E is a group's entry with a value in every particle
%   (a group that lacks the key, none, has it open: never drawn there).
defined_entry(E) :- E \== none, entry_status(E, defined).

source_column(none, '$none') :- !.
source_column(E, C) :- entry_column(E, C).

common_arity([E|Es], Arity) :-
    entry_arity(E, A),
    (   forall(( member(E1, Es), E1 \== none ), ( entry_arity(E1, A1), A1 == A ))
    ->  Arity = A
    ;   Arity = unknown
    ).

                 /*******************************
                 *           RENAMING           *
                 *******************************/

%!  rename_table(+Table0, +Moves:list(pair), +Ps:list(integer), +N, -Table) is det.
%
%   Table (none if Table0 is none): Table0 of N particles with the
%   constants renamed by Moves (ddc_rename.pl; filter_rename/3) in the
%   particles Ps (sorted): under each key K, a particle of Ps holds its
%   value of the key that K renames, itself renamed ('$u' where it had
%   none: not drawn), the others their own value of K.  An entry the
%   rename leaves as it is (its key names no moved constant, nor do the
%   values of Ps) is Table0's own; any other is a new column, so a column
%   of one value (same/1, possibly another table's, see resampled_entry/4)
%   is never written.  Table0 is not changed.
rename_table(none, _, _, _, none) :- !.
rename_table(Tab0, Moves, Ps, N, Tab) :-
    table_new(Tab),
    findall(K, table_match(Tab0, K, _), Ks0),
    maplist(renamed_key(Moves), Ks0, Ks1),
    append(Ks0, Ks1, Ks2),
    sort(Ks2, Ks),
    maplist(inverse_move, Moves, Inverse),
    forall(member(K, Ks), rename_entry(Tab0, Moves, Inverse, Ps, N, K, Tab)).

inverse_move(Old-New, New-Old).

%   renamed_key(+Moves, +K, -K1): a table's key renamed: a random
%   variable's arguments; '$inst'(N/A) (a predicate's instances) stays.
renamed_key(Moves, K, K1) :-
    (   K = '$inst'(_) -> K1 = K ; rename_arguments(Moves, K, K1) ).

%   renamed_value(+Moves, +K, +V, -V1): a value under key K renamed: each
%   instance's arguments in a '$inst' list, else the value throughout.
renamed_value(Moves, K, V, V1) :-
    (   K = '$inst'(_), is_list(V)
    ->  maplist(rename_arguments(Moves), V, V1)
    ;   rename_term(Moves, V, V1)
    ).

%   rename_entry(+Tab0, +Moves, +Inverse, +Ps, +N, +K, !Tab): K's entry of
%   the renamed table (rename_table/5).
rename_entry(Tab0, Moves, Inverse, Ps, N, K, Tab) :-
    renamed_key(Inverse, K, K0),
    (   table_get(Tab0, K, E) -> true ; E = none ),
    (   table_get(Tab0, K0, E0) -> true ; E0 = none ),
    (   K0 == K, E \== none,
        entry_column(E, C),
        forall(member(I, Ps), ( col_arg(I, C, V), renamed_value(Moves, K, V, V1), V1 == V ))
    ->  table_link(Tab, K, E)
    ;   entry_column_or_none(E, C),
        entry_column_or_none(E0, C0),
        col_new(N, '$u', C1),
        renamed_column(1, N, Ps, Moves, K, C, C0, C1),
        (   K = '$inst'(_) -> A = none ; A = unknown ),
        linked_entry(C1, open, A, E1),
        duplicate_term(E1, E2),
        settle(E2),
        table_link(Tab, K, E2)
    ).

entry_column_or_none(E, C) :-
    (   E == none -> C = none ; entry_column(E, C) ).

%   renamed_column(+I, +N, +Ps, +Moves, +K, +C, +C0, !C1): arguments I..N
%   of C1: a particle of Ps (sorted, those from I on) its value in C0
%   renamed, any other its value in C ('$u' for a column none).
renamed_column(I, N, Ps, Moves, K, C, C0, C1) :-
    (   I > N
    ->  true
    ;   (   Ps = [I|Ps1]
        ->  (   C0 == none -> V = '$u'
            ;   col_arg(I, C0, V0), renamed_value(Moves, K, V0, V)
            )
        ;   Ps1 = Ps,
            (   C == none -> V = '$u' ; col_arg(I, C, V) )
        ),
        col_setarg(I, C1, V),
        I1 is I+1,
        renamed_column(I1, N, Ps1, Moves, K, C, C0, C1)
    ).
