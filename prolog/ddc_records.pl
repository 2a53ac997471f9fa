/*  ddc_records.pl -- records with named fields for the engine's modules.

    The engine keeps its state in compound terms (a world, a filter, a
    batch of particles) that its hot paths read and update in place.  This
    module lets a module declare such a record once, by the names of its
    fields, and then read and write the fields by name; the accessors are
    compiled inline, to the same arg/3, setarg/3, nb_setarg/3 and nb_linkarg/3
    instructions that positional code would use, so naming a field costs
    nothing at run time.
*/

:- module(ddc_records,
          [ op(1150, fx, record_type)
          ]).

:- use_module(library(error)).
:- use_module(library(lists)).
:- use_module(library(apply)).
:- use_module(library(pairs)).

/** <module> Records with named fields, accessed inline

A module declares a record type by its functor and the names of its
fields:

    :- use_module(ddc_records).
    :- record_type world(program, store, time).

The declaration defines and exports, for each field F at position I:

  - world_F(+World, -Value): Value is the field (arg(I, World, Value));
  - set_world_F(!World, +Value): setarg(I, World, Value) (backtrackable);
  - nb_set_world_F(!World, +Value): nb_setarg(I, World, Value);
  - nb_link_world_F(!World, +Value): nb_linkarg(I, World, Value) (no
    copy: Value must be a term that outlives the update, see nb_linkarg/3);

and new_world(-World), a record whose fields are fresh variables, and
world_fields(-Names), the field names in order.  In every module that
loads ddc_records (the declaring one and those importing its
accessors), a call to an accessor is compiled to the arg/setarg/nb_setarg/nb_linkarg
goal itself.  The accessors remain ordinary predicates, so they can also
be called from the top level or passed to maplist/3.

Field names must be distinct within a record; two records declared in
the same program must not generate the same accessor name.
*/

%!  field(?Accessor:atom, ?Kind:oneof([get,set,nb_set,nb_link]), ?Index:integer,
%!        ?Module:atom) is nondet.
%
%   Accessor/2 reads (get) or writes (set, nb_set, nb_link) argument Index of the
%   record; Module declared it.

:- dynamic field/4.

%!  record_type(+Template:compound) is det.
%
%   The directive form; expanded at load time (see the module
%   documentation).  Called as a goal it raises an error.
%
%   @error permission_error(call, directive, record_type(Template))

:- multifile system:term_expansion/2.
:- multifile system:goal_expansion/2.

system:term_expansion((:- record_type(Template)), Clauses) :-
    prolog_load_context(module, Module),
    record_clauses(Template, Module, Clauses).

system:goal_expansion(Goal, Expanded) :-
    compound(Goal),
    compound_name_arity(Goal, Name, 2),
    field(Name, Kind, Index, Declarer),
    prolog_load_context(module, Module),
    (   Module == Declarer
    ->  true
    ;   predicate_property(Module:Goal, imported_from(Declarer))
    ),
    arg(1, Goal, Record),
    arg(2, Goal, Value),
    inline(Kind, Index, Record, Value, Expanded).

inline(get,    I, R, V, arg(I, R, V)).
inline(set,    I, R, V, setarg(I, R, V)).
inline(nb_set, I, R, V, nb_setarg(I, R, V)).
inline(nb_link, I, R, V, nb_linkarg(I, R, V)).

%!  record_clauses(+Template, +Module, -Clauses) is det.
%
%   @error type_error(record_template, Template) unless Template is a
%          compound whose arguments are distinct atoms.

record_clauses(Template, Module, Clauses) :-
    (   compound(Template),
        compound_name_arguments(Template, Functor, Names),
        maplist(atom, Names),
        sort(Names, Sorted), length(Sorted, N), length(Names, N)
    ->  true
    ;   type_error(record_template, Template)
    ),
    length(Fresh, N),
    New =.. [Functor|Fresh],
    atom_concat(new_, Functor, NewName),
    atom_concat(Functor, '_fields', FieldsName),
    NewHead =.. [NewName, New],
    FieldsHead =.. [FieldsName, Names],
    findall(Clause-PI,
            ( nth1(I, Names, F),
              accessor(Kind, Functor, F, Accessor),
              retractall(field(Accessor, _, _, _)),   % a reload declares it again
              assertz(field(Accessor, Kind, I, Module)),
              inline(Kind, I, R, V, Body),
              Head =.. [Accessor, R, V],
              Clause = (Head :- Body),
              PI = Accessor/2
            ),
            Pairs),
    pairs_keys_values(Pairs, Accessors, PIs),
    foldl(export_conj, PIs, FieldsName/1, Exports0),
    Clauses = [ (:- export((NewName/1, Exports0))),
                NewHead,
                FieldsHead
              | Accessors
              ].

%   (Not a yall lambda: loading library(yall) here would turn on its goal
%   expansion in every file compiled after the engine, which gives a
%   lambda's free variables other semantics: copied at the call without
%   it, shared with the clause with it.)
export_conj(PI, E0, (PI, E0)).

accessor(get,    Functor, F, A) :- atomic_list_concat([Functor, '_', F], A).
accessor(set,    Functor, F, A) :- atomic_list_concat([set_, Functor, '_', F], A).
accessor(nb_set, Functor, F, A) :- atomic_list_concat([nb_set_, Functor, '_', F], A).
accessor(nb_link, Functor, F, A) :- atomic_list_concat([nb_link_, Functor, '_', F], A).
