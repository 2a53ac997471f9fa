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

and new_world(-World), a record whose fields are fresh variables,
make_world(+Fields, -World), a record with the fields given as a list
of Name(Value) (the others fresh variables), e.g.
make_world([store(S), time(0)], W), and world_fields(-Names), the field
names in order.  In every module that loads ddc_records (the declaring
one and those importing its accessors), a call to an accessor is
compiled to the arg/setarg/nb_setarg/nb_linkarg goal itself, and a call
of make_world/2 whose list is known at compile time to the unification
World = world(...).  The accessors remain ordinary predicates, so they
can also be called from the top level or passed to maplist/3.

Field names must be distinct within a record.  Two modules may not
declare records that generate the same accessor name (an error names
both modules); a module that is loaded again declares its own afresh.
*/

%!  field(?Accessor:atom, ?Kind:oneof([get,set,nb_set,nb_link]), ?Index:integer,
%!        ?Module:atom) is nondet.
%
%   Accessor/2 reads (get) or writes (set, nb_set, nb_link) argument Index of the
%   record; Module declared it.
%
%!  constructor(?Name:atom, ?Functor:atom, ?Fields:list(atom), ?Module:atom) is nondet.
%
%   Name/2 makes records Functor(...) with the field names Fields; Module
%   declared it.

:- dynamic field/4, constructor/4.

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
    (   field(Name, Kind, Index, Declarer)
    ->  visible(Goal, Declarer),
        arg(1, Goal, Record),
        arg(2, Goal, Value),
        inline(Kind, Index, Record, Value, Expanded)
    ;   constructor(Name, Functor, Names, Declarer),
        visible(Goal, Declarer),
        arg(1, Goal, Fields),
        is_list(Fields),
        arg(2, Goal, Record),
        catch(record_term(Functor, Names, Fields, Term), _, fail)   % (else: at run time)
    ->  Expanded = (Record = Term)
    ).

%   visible(+Goal, +Declarer): Goal, compiled in the current module, is
%   the accessor that Declarer defines (not a predicate of the same name).
visible(Goal, Declarer) :-
    prolog_load_context(module, Module),
    (   Module == Declarer
    ->  true
    ;   predicate_property(Module:Goal, imported_from(Declarer))
    ).

%!  make_record(+Functor, +Names, +Fields, -Record) is det.
%
%   The run-time part of make_<record>/2: Record is Functor(...) with the
%   fields of Fields (a list of Name(Value)), the others fresh variables.
%
%   @error type_error(record_field, F) if an element of Fields is not
%          Name(Value); existence_error(record_field, Name) if Name is not
%          a field of the record.

make_record(Functor, Names, Fields, Record) :-
    must_be(list, Fields),
    record_term(Functor, Names, Fields, Record).

record_term(Functor, Names, Fields, Record) :-
    length(Names, N),
    functor(Record, Functor, N),
    maplist(set_field(Names, Record), Fields).

set_field(Names, Record, Field) :-
    (   compound(Field), compound_name_arguments(Field, Name, [Value])
    ->  true
    ;   type_error(record_field, Field)
    ),
    (   nth1(I, Names, Name)
    ->  arg(I, Record, Value)
    ;   functor(Record, Functor, _),
        existence_error(record_field, Functor:Name)
    ).

inline(get,    I, R, V, arg(I, R, V)).
inline(set,    I, R, V, setarg(I, R, V)).
inline(nb_set, I, R, V, nb_setarg(I, R, V)).
inline(nb_link, I, R, V, nb_linkarg(I, R, V)).

%!  record_clauses(+Template, +Module, -Clauses) is det.
%
%   @error type_error(record_template, Template) unless Template is a
%          compound whose arguments are distinct atoms.
%   @error permission_error(declare, record_accessor, Accessor) if
%          another module declared a record with that accessor.

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
    atom_concat(make_, Functor, MakeName),
    atom_concat(Functor, '_fields', FieldsName),
    NewHead =.. [NewName, New],
    MakeHead =.. [MakeName, Fields, Record],
    FieldsHead =.. [FieldsName, Names],
    findall(Accessor, ( member(F, Names), accessor(_, Functor, F, Accessor) ), Generated),
    forall(( member(A, [MakeName|Generated]),
             ( field(A, _, _, Other) ; constructor(A, _, _, Other) ),
             Other \== Module ),
           permission_error(declare, record_accessor, A)),
    forall(member(A, [MakeName|Generated]),     % a reload declares them again
           ( retractall(field(A, _, _, _)), retractall(constructor(A, _, _, _)) )),
    assertz(constructor(MakeName, Functor, Names, Module)),
    findall(Clause-PI,
            ( nth1(I, Names, F),
              accessor(Kind, Functor, F, Accessor),
              assertz(field(Accessor, Kind, I, Module)),
              inline(Kind, I, R, V, Body),
              Head =.. [Accessor, R, V],
              Clause = (Head :- Body),
              PI = Accessor/2
            ),
            Pairs),
    pairs_keys_values(Pairs, Accessors, PIs),
    foldl(export_conj, PIs, FieldsName/1, Exports0),
    Clauses = [ (:- export((NewName/1, MakeName/2, Exports0))),
                NewHead,
                (MakeHead :- ddc_records:make_record(Functor, Names, Fields, Record)),
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
