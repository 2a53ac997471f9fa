/*  ddc_batch_col.pl -- the batched filter's columns: C arrays, or Prolog terms.

    Part of the batched particle filter (ddc_batch.pl, the API): a column
    holds the particles' values of a random variable at a time, one per
    particle, read and written by particle index.  Two representations,
    chosen once, when this module is loaded:

      foreign  the compiled library prolog/ddc/batch/c/ddc_columns.c (built by
               scripts/setup.sh next to its source): a column is a blob of
               C arrays (number tuples as floats, atoms, lists of ground
               items, other terms recorded), and the loops the engine runs
               most run in C (docs/batched-filter.md, "Columns in C");
      prolog   a term c(V1, ..., VN) read with arg/3 and written with
               nb_setarg/3, every loop in Prolog: the engine as it was
               before the library, used when the library is not built (an
               installed wheel, a machine without a C compiler) or when
               the environment variable DDC_COLUMNS is `prolog`.

    Both give the same answers; the draws differ (the library draws from a
    generator of its own, seeded from the filter's random stream), so the
    same seed gives other particles from each (docs/batched-filter.md).
*/

:- module(ddc_batch_col,
          [ col_backend/1,              % -Backend
            col_collect_garbage/0,
            col_has_ref/1,              % @Term
            col_new/3,                  % +N, +Value, -Column
            col_arg/3,                  % +I, +Column, ?Value
            col_setarg/3,               % +I, !Column, +Value
            col_is_u/2,                 % +I, +Column
            col_size/2,                 % +Column, -N
            col_list/2,                 % +Column, -Values
            col_from_list/2,            % +Values, -Column
            col_uncomputed/3,           % +Ps, +Column, -Missing
            col_defined_at/3,           % +Ps, +Column, -Defined
            col_set_each/3,             % +Ps, !Column, +Value
            col_status/2,               % +Column, -Status
            col_all_same/3,             % +Ps, +Column, +I0
            col_gather/3,               % +Sources, +Pairs, -Column
            col_plan_size/2,            % +Pairs, -N
            ps_all/2,                   % +N, -Ps
            ps_list/2,                  % +Ps, -List
            ps_size/2,                  % +Ps, -K
            ps_first/2,                 % +Ps, -I
            ps_subtract/3,              % +Ps0, +Ps1, -Ps
            ps_intersection/3,          % +Ps0, +Ps1, -Ps
            ps_union/3,                 % +Ps0, +Ps1, -Ps
            ps_union/2,                 % +Pss, -Ps
            % fast paths (see below)
            col_num_arity/2,            % +Column, -K
            col_rows/4,                 % +Column, ?Width, -Floats, ?Tail
            col_row_width/2,            % +Column, -Width
            col_pack_rows/3,            % +Columns, +Width, -Rows
            col_floats_into/4,          % +Rows, +Address, +Capacity, -N
            col_floats_list/2,          % +Rows, -Floats
            col_draw_gauss/5,           % +Ps, +MeanColumn, +Factor, !Out, +Seed
            col_weigh_gauss/7,          % +Ps, +MeanColumn, +Factor, +LogNorm, +V, !Done, !LW
            col_vm_test/7,              % +Ps, +Columns, +Code, +Op, +A, +B, -Out
            col_vm_instance/5,          % +Ps, +Columns, +Code, +Registers, !Column
            col_copy_each/3,            % +Ps, +From, !Column
            col_test/3,                 % +Ps, +Goal, -Out
            col_instance/3,             % +Ps, +Template, !Column
            col_partition/3,                % +Ps, +Columns, -Groups
            col_draw_uniform/4,         % +Ps, +ListColumn, !Column, +Seed
            col_select_eq/5,            % +Ps, +Column, +Value, +Eq, -Out
            col_sources/3,              % +Indices, +Sizes, -Pairs
            col_vm_finite/7,            % +Ps, +Columns, +Code, +Registers, +Values, !C, +Seed
            col_append_each/3,          % +Ps, !ListColumn, +Value
            col_select_unify/4,         % +Ps, +Column, +Pattern, -Out
            col_with_arity/4,           % +Ps, +Column, +K, -Out
            col_sets_each/3,            % +Ps, +ListColumn, !Column
            col_weights_update/6,       % +LW0, +Step, -LW, -Inc, -ESS, -Infinite
            col_systematic_indices/3    % +LogWeights, +U, -Indices
          ]).

:- use_module(library(ordsets)).
:- use_module(library(lists), [numlist/3]).

:- set_prolog_flag(optimise, true).

/** <module> Columns of the batched filter

A particle index is an integer 1..N.  A column's value for a particle is
'$u' (not drawn yet), '$undef' (no clause applies) or the particle's
value.  A column is updated in place, as nb_setarg/3 updates a term: the
change is not undone on backtracking.

col_backend/1 says which representation is in use.  The predicates of
the export list from col_num_arity/2 on are fast paths: they fail where
the library is not loaded (or does not handle the values), and the caller
then runs its loop in Prolog; a fast path that fails has written nothing.

A batch (ps_all/2) is a set of particle indices: with the library a blob,
a C array passed from call to call as it is; else, and wherever a caller
gives one, a sorted list of integers.  A call given lists gives lists.
With the library, a column whose particles all hold one value stores one
cell (docs/batched-filter.md, "Columns in C").
*/

%   The interface version the Prolog side expects of the library
%   (DDC_COLUMNS_VERSION in prolog/ddc/batch/c/ddc_columns.c).
columns_version(5).

%!  ps_all(+N, -Ps) is det.
%!  ps_list(+Ps, -List:list(integer)) is det.
%!  ps_size(+Ps, -K) is det.
%!  ps_first(+Ps, -I) is semidet.
%
%   A batch is a set of particle indices: a sorted list of integers 1..N
%   or, where the library is loaded, a blob holding the same set as a C
%   array (the engine's batches: passed from call to call as they are,
%   where a list is walked and built again by each); the empty batch is
%   [] either way.  ps_all/2: every particle 1..N; ps_list/2: the indices
%   as a list (for a loop in Prolog); ps_size/2: how many; ps_first/2: the
%   least (fails on []).

%!  ps_subtract(+Ps0, +Ps1, -Ps) is det.
%!  ps_intersection(+Ps0, +Ps1, -Ps) is det.
%!  ps_union(+Ps0, +Ps1, -Ps) is det.
%!  ps_union(+Pss, -Ps) is det.
%
%   ord_subtract/3, ord_intersection/3 and ord_union/3,2 on batches (sorted
%   lists of particle indices), in C where the library is loaded.
ps_subtract(A, B, C) :-
    (   B == [] -> C = A
    ;   A == B -> C = []
    ;   '$ps_subtract'(A, B, C0) -> C = C0
    ;   ord_subtract(A, B, C)
    ).
ps_intersection(A, B, C) :-
    (   A == B -> C = A
    ;   '$ps_intersection'(A, B, C0) -> C = C0
    ;   ord_intersection(A, B, C)
    ).
ps_union(A, B, C) :-
    (   B == [] -> C = A
    ;   A == [] -> C = B
    ;   '$ps_union'(A, B, C0) -> C = C0
    ;   ord_union(A, B, C)
    ).
ps_union(Ls, C) :-
    (   Ls == [] -> C = []
    ;   Ls = [C0] -> C = C0
    ;   '$ps_union'(Ls, C0) -> C = C0
    ;   ord_union(Ls, C)
    ).

%!  col_collect_garbage is det.
%
%   Frees the columns no longer referenced once more than
%   col_gc_bytes/1 of them were made since the last time (the library's
%   columns are blobs, freed by the atom garbage collector, which counts
%   atoms, not bytes): called after each step.  Nothing to do for terms.
col_collect_garbage :-
    (   col_backend(foreign), col_gc_bytes(Limit), col_gc_due(Limit)
    ->  garbage_collect_atoms
    ;   true
    ).

%   col_gc_bytes(-Bytes): how many bytes of new columns call for a
%   collection (a few steps of 10,000 particles).
col_gc_bytes(64_000_000).

%   load_columns: the compiled library is loaded, of the expected version
%   (silently not, if it is not built or DDC_COLUMNS=prolog; a library
%   that does not load or is of another version is reported).
load_columns :-
    \+ getenv('DDC_COLUMNS', prolog),
    prolog_load_context(directory, Dir),
    directory_file_path(Dir, 'c/ddc_columns', Base),
    current_prolog_flag(shared_object_extension, Ext),
    file_name_extension(Base, Ext, Lib),
    exists_file(Lib),
    (   catch(load_foreign_library(Lib), E,
              ( print_message(warning, ddc_columns(not_loaded(Lib, E))), fail ))
    ->  columns_version(V0),
        (   catch(col_version(V), _, fail), V == V0
        ->  true
        ;   print_message(warning, ddc_columns(version(Lib, V0))),
            fail
        )
    ).

:- multifile prolog:message//1.
prolog:message(ddc_columns(not_loaded(Lib, E))) -->
    [ 'The batched filter''s column library ~w does not load (~q): '-[Lib, E],
      'columns in Prolog (slower); run scripts/setup.sh to build it again' ].
prolog:message(ddc_columns(version(Lib, V))) -->
    [ 'The batched filter''s column library ~w is not of version ~w: '-[Lib, V],
      'columns in Prolog (slower); run scripts/setup.sh to build it again' ].

:- if(load_columns).

%!  col_backend(-Backend) is det.
%
%   foreign (the compiled library) or prolog (terms c(V1, ..., VN)).
col_backend(foreign).

:- else.

col_backend(prolog).

col_gc_due(_) :- fail.

ps_all(N, Ps) :- numlist(1, N, Ps).
ps_list(Ps, Ps).
ps_size(Ps, K) :- length(Ps, K).
ps_first([I|_], I).

%!  col_has_ref(@Term) is semidet.
%
%   Term holds a column reference '$c'(C, P, V) or a deferred expression
%   '$x'(E) (ddc_batch_columns.pl's has_column/1; in C where the library
%   is loaded).
col_has_ref(T) :-
    compound(T),
    (   T = '$c'(_, _, _) -> true ; T = '$x'(_) -> true ; arg(_, T, A), col_has_ref(A) ), !.

%!  col_new(+N, +Value, -Column) is det.
%
%   A column of N particles, each holding Value.
col_new(N, V, C) :-
    functor(C, c, N),
    fill(N, C, V).

fill(0, _, _) :- !.
fill(I, C, V) :- arg(I, C, V), I1 is I-1, fill(I1, C, V).

%!  col_arg(+I, +Column, ?Value) is semidet.
col_arg(I, C, V) :- arg(I, C, V).

%!  col_setarg(+I, !Column, +Value) is det.
col_setarg(I, C, V) :- nb_setarg(I, C, V).

%!  col_is_u(+I, +Column) is semidet.
%
%   Particle I's value is not drawn yet.
col_is_u(I, C) :- arg(I, C, V), V == '$u'.

%!  col_size(+Column, -N) is det.
col_size(C, N) :- functor(C, _, N).

%!  col_list(+Column, -Values:list) is det.
col_list(C, Vs) :- C =.. [_|Vs].

%!  col_from_list(+Values:list, -Column) is det.
col_from_list(Vs, C) :- C =.. [c|Vs].

%!  col_uncomputed(+Ps, +Column, -Missing) is det.
%
%   Missing: the particles of Ps whose value is not drawn yet.
col_uncomputed([], _, []).
col_uncomputed([I|Is], C, Ps) :-
    arg(I, C, V),
    (   V == '$u' -> Ps = [I|Ps1] ; Ps = Ps1 ),
    col_uncomputed(Is, C, Ps1).

%!  col_defined_at(+Ps, +Column, -Defined) is det.
%
%   Defined: the particles of Ps that have a value.
col_defined_at([], _, []).
col_defined_at([I|Is], C, Ps) :-
    arg(I, C, V),
    (   ( V == '$u' ; V == '$undef' ) -> Ps = Ps1 ; Ps = [I|Ps1] ),
    col_defined_at(Is, C, Ps1).

%!  col_set_each(+Ps, !Column, +Value) is det.
%
%   Each particle of Ps whose value is not drawn yet gets Value.
col_set_each([], _, _).
col_set_each([I|Is], C, V) :-
    (   arg(I, C, U), U == '$u' -> nb_setarg(I, C, V) ; true ),
    col_set_each(Is, C, V).

%!  col_status(+Column, -Status) is det.
%
%   open (a particle lacks its value), same(V) (every particle holds V),
%   defined (values, not all the same, none '$undef') or mixed.
col_status(C, S) :-
    functor(C, _, N),
    arg(1, C, V1),
    column_status(N, C, V1, same, S0),
    (   S0 == same -> S = same(V1) ; S = S0 ).

column_status(0, _, _, S, S) :- !.
column_status(I, C, V1, S0, S) :-
    arg(I, C, V),
    (   V == '$u' -> S = open
    ;   (   S0 == same, V == V1 -> S1 = same
        ;   S0 == mixed -> S1 = mixed
        ;   V == '$undef' -> S1 = mixed
        ;   V1 == '$undef' -> S1 = mixed
        ;   S1 = defined
        ),
        I1 is I-1,
        column_status(I1, C, V1, S1, S)
    ).

%!  col_rows(+Column, ?Width, -Floats, ?Tail) is semidet.
%
%   Fast path of a column read as rows of Width floats (filter_rows/6),
%   NaN rows where a particle has no value (fails here).
col_rows(_, _, _, _) :- fail.

%!  col_pack_rows(+Columns:list, +Width, -Rows) is semidet.
%!  col_floats_into(+Rows, +Address, +Capacity, -N) is semidet.
%
%   The rows of col_rows/4 of each column in turn, as a blob of doubles
%   (an atom: not copied out of the filter's engine, as a list of floats
%   is), and its N doubles copied into the memory at Address that holds
%   Capacity doubles (a numpy array's: the Python bridge reads many rows
%   without converting each float).  col_floats_list/2: the doubles as a
%   list.  They fail here (no library).
col_pack_rows(_, _, _) :- fail.
col_floats_into(_, _, _, _) :- fail.
col_floats_list(_, _) :- fail.

%!  col_weights_update(+LogWeights0, +StepLogWeights, -LogWeights, -Increment, -ESS,
%!                     -Infinite) is semidet.
%
%   Fast path of ddc_weights:weights_update/6 (the same operations in the
%   same order, in C; fails here).
col_weights_update(_, _, _, _, _, _) :- fail.

%!  col_systematic_indices(+LogWeights, +U, -Indices) is semidet.
%
%   Fast path of ddc_weights:resample_log_weights/5 for the systematic
%   scheme (the same operations in the same order, in C; fails here).
col_systematic_indices(_, _, _) :- fail.

%!  col_row_width(+Column, -Width) is semidet.
%
%   Every value of Column is a tuple of Width floats ('$u' and '$undef'
%   aside; Width 0 if there is none): fast path of a read as rows (fails
%   here).
col_row_width(_, _) :- fail.

%!  col_all_same(+Ps, +Column, +I0) is semidet.
%
%   Every particle of Ps holds particle I0's value (==).
col_all_same(Ps, C, I0) :-
    arg(I0, C, V),
    all_same(Ps, C, V).

all_same([], _, _).
all_same([I|Is], C, V) :- arg(I, C, V1), V1 == V, all_same(Is, C, V).

%!  col_num_arity(+Column, -K) is semidet.
%
%   Every particle holds a tuple of K floats (fast path: fails here).
col_num_arity(_, _) :- fail.

%!  col_gather(+Sources:list, +Pairs:list, -Column) is det.
%
%   Column's particle J is particle L of the G-th column of Sources, for
%   the J-th pair G-L of Pairs (1-based); a source '$none' gives '$u'.
col_gather(Srcs, Pairs, C) :-
    Src =.. [s|Srcs],
    pair_values(Pairs, Src, Vs),
    C =.. [c|Vs].

%!  col_plan_size(+Pairs, -N) is det.
%
%   The number of particles of a group's sources (col_sources/3's, or a
%   list of G-L pairs).
col_plan_size(Pairs, N) :- length(Pairs, N).

pair_values([], _, []).
pair_values([G-L|Ps], Src, [V|Vs]) :-
    arg(G, Src, C),
    (   C == '$none' -> V = '$u' ; arg(L, C, V) ),
    pair_values(Ps, Src, Vs).

%!  col_draw_gauss(+Ps, +MeanColumn, +Factor, !Out, +Seed) is semidet.
%
%   Fast path of gaussian draws (fails here).
col_draw_gauss(_, _, _, _, _) :- fail.

%!  col_weigh_gauss(+Ps, +MeanColumn, +Factor, +LogNorm, +V, !Done, !LW) is semidet.
%
%   Fast path of gaussian log densities (fails here).
col_weigh_gauss(_, _, _, _, _, _, _) :- fail.

%!  col_vm_test(+Ps, +Columns, +Code, +Op, +A, +B, -Out) is semidet.
%!  col_vm_instance(+Ps, +Columns, +Code, +Registers, !Column) is semidet.
%!  col_copy_each(+Ps, +From, !Column) is semidet.
%
%   Fast paths of loops of arithmetic and copies over a batch (fail here;
%   ddc_batch_columns.pl compiles them).
col_vm_test(_, _, _, _, _, _, _) :- fail.

%!  col_test(+Ps, +Goal, -Out) is semidet.
%!  col_instance(+Ps, +Template, !Column) is semidet.
%
%   Fast paths of a comparison over a batch (Out the particles where it
%   holds) and of each particle's instance of a template, compiled from
%   the goal's own terms (column references, deferred expressions); fail
%   here.
col_test(_, _, _) :- fail.
col_instance(_, _, _) :- fail.
col_vm_instance(_, _, _, _, _) :- fail.
col_copy_each(_, _, _) :- fail.

%!  col_partition(+Ps, +Columns, -Groups) is semidet.
%!  col_draw_uniform(+Ps, +ListColumn, !Column, +Seed) is semidet.
%
%   Fast paths of a partition of a batch by its values and of uniform draws
%   from lists (fail here).
col_partition(_, _, _) :- fail.
col_draw_uniform(_, _, _, _) :- fail.

%!  col_select_eq(+Ps, +Column, +Value, +Eq, -Out) is semidet.
%!  col_sources(+Indices, +Sizes, -Pairs) is semidet.
%
%   Fast paths of a test V == Value (Eq true) or V \== Value over a batch
%   and of the ancestors of a resampling, per group (in the library a blob
%   that col_gather/3 reads as the list of Group-Index pairs; fail here).
col_select_eq(_, _, _, _, _) :- fail.
col_sources(_, _, _) :- fail.

%!  col_vm_finite(+Ps, +Columns, +Code, +Registers, +Values, !Column, +Seed) is semidet.
%
%   Fast path of draws of finite distributions whose probabilities are
%   computed over the batch (fails here).
col_vm_finite(_, _, _, _, _, _, _) :- fail.

%!  col_append_each(+Ps, !ListColumn, +Value) is semidet.
%!  col_select_unify(+Ps, +Column, +Pattern, -Out) is semidet.
%
%   Fast paths of a value appended to each particle's list and of the
%   particles whose value unifies with Pattern or is a number =:= to it
%   (fail here).
col_append_each(_, _, _) :- fail.
col_select_unify(_, _, _, _) :- fail.

%!  col_with_arity(+Ps, +Column, +K, -Out) is semidet.
%!  col_sets_each(+Ps, +ListColumn, !Column) is semidet.
%
%   Fast paths of the particles whose value is a tuple of K elements or
%   more and of each particle's list without repeats (fail here).
col_with_arity(_, _, _, _) :- fail.
col_sets_each(_, _, _) :- fail.

'$ps_subtract'(_, _, _) :- fail.
'$ps_intersection'(_, _, _) :- fail.
'$ps_union'(_, _, _) :- fail.
'$ps_union'(_, _) :- fail.

:- endif.
