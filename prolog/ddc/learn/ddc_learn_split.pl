/*  ddc_learn_split.pl -- split learning data into a training and a test
    file for held-out evaluation (`ddc split`).

    The test facts must form worlds of their own: a target's test groundings
    and the evidence their clauses read come from entities the training
    data never mention.  The facts are grouped into units (the connected
    components of the graph that links the constants of each fact, or the
    constants of one type with everything nearest to them); whole units go
    to the test side.
*/

:- module(ddc_learn_split,
          [ learn_split_files/3,        % +Files, +Options, -Stats
            learn_fold_files/3          % +Files, +Options, -Stats
          ]).

:- use_module(library(lists)).
:- use_module(library(apply)).
:- use_module(library(assoc)).
:- use_module(library(error)).
:- use_module(library(option)).
:- use_module(library(pairs)).
:- use_module(library(ordsets)).
:- use_module(library(random)).
:- use_module(ddc_learn_data).
:- use_module(ddc_learn_bias, [bias_term/2]).

/** <module> Splitting learning data into training and test worlds

learn_split_files/3 reads a data set (docs/learning.md: facts, background
knowledge and declarative bias, in the project's own dialect or DreaML's)
and writes two data files of the same dialect: a training part and a test
part.  Every item that is not a fact is written to both: directives, bias
declarations, background rules, non-ground clauses, and the ground clauses
of predicates that Prolog rules or non-ground clauses define (DreaML's
`list2set([], [])` is the base case of a background predicate, not data).
Each fact goes to the side of its *unit*:

  - The *constants* of a fact are the atomic arguments of its key: a random
    variable's key arguments, not its value (`gender(c1) ~= m` and DreaML's
    `gender(c1, m)` have the constant c1; DreaML's relation
    `hasAccount(c1, a1, true)` has c1 and a1), an atom's arguments.
    Time-indexed keys are read as the learner reads them (`p(X):t+1` is
    p_t1(X)).
  - Without unit(Type), a unit is a connected component of the graph whose
    nodes are the constants and where the constants of one fact are linked.
  - With unit(Type), the units are the constants in argument positions of
    type Type (type/1, DreaML's base/1).  Every other constant belongs to
    the unit nearest to it in the graph: breadth-first from all units at
    once, one distance at a time, the facts of each step in the data's
    order, so that a constant equally near two units goes to the unit of
    the first fact that reaches it.  The search does not go on through
    another unit's constant: two units are never merged through a shared
    neighbour.  Constants that no unit reaches form a unit per connected
    component.

The units are shuffled (set_random(seed(Seed)), random_permutation/2) and
put on the test side in that order until it holds at least the fraction of
the facts (always one unit at least, and one unit at least stays for
training).  A fact goes to the side that holds all its constants; a fact
whose constants are on both sides is *cut* (written to neither).  A fact
without constants (`rain ~= true`) goes to both.

The items keep their order; each is written back as a term that the same
readers read to the same term (variables by their source names).  The two
files are written to temporary files in their directories and renamed only
once both are complete, so a failed run never leaves half a file.

Errors are error(ddc_learn(Cause, File:Line), _) and print as
`File:Line: cause`, as the data reader's do.
*/

                 /*******************************
                 *             SPLIT            *
                 *******************************/

%!  learn_split_files(+Files:list, +Options:list, -Stats:dict) is det.
%
%   Split the data of Files into a training file and a test file.
%   Options:
%
%     - train(+File), test(+File): the two outputs (required; created or
%       replaced).
%     - fraction(+F): the test side's share of the facts, 0 < F < 1
%       (default 0.2).
%     - seed(+S): the seed of the units' order (default 0).
%     - unit(+Type): split by the constants of that argument type.
%
%   Stats is `_{train: NTrain, test: NTest, cut: NCut, units: NUnits,
%   test_units: K, both: NBoth}`: the facts written to the training part
%   only, to the test part only, to neither, the number of units, of test
%   units, and of facts without constants (written to both).
%
%   @error ddc_learn(Cause, File:Line): bad data (as learn_data_load/3),
%          one connected world only (one_world/1), an unknown unit type
%          (unknown_unit_type/2), one constant of the unit type only
%          (one_unit/2), no fact with a constant of the unit type
%          (no_unit_constants/1), no facts (no_facts), files of both
%          dialects (mixed_dialects/4), an output that is an input
%          (output_is_input), both outputs the same file (same_outputs),
%          an output in a directory that does not exist
%          (no_such_directory/1).
%   @error ddc_learn(missing_option(Name), learn_split_files/3) without
%          train(File) or test(File).
%   @error domain_error(open_interval(0, 1), F) for a bad fraction; type
%          errors for ill-typed options.
learn_split_files(Files, Options, Stats) :-
    must_be(list, Files),
    must_be(list, Options),
    (   Files == [] -> domain_error(non_empty_list, Files) ; true ),
    split_options(Options, Opts),
    maplist(ddc_learn_data:resolve_data_file, Files, Paths),
    check_outputs(Paths, Opts),
    setup_call_cleanup(learn_data_load(Paths, [targets(false)], Data),
                       split_data(Data, Paths, Opts, Stats),
                       learn_data_free(Data)).

%   split_options(+Options, -Settings): split_settings(Train, Test,
%   Fraction, Seed, Unit), the outputs as absolute file names, Unit none or
%   unit(Type).
split_options(Options, split_settings(Train, Test, F, Seed, Unit)) :-
    output_option(train, Options, Train),
    output_option(test, Options, Test),
    option(fraction(F), Options, 0.2),
    must_be(number, F),
    (   F > 0, F < 1 -> true ; domain_error(open_interval(0, 1), F) ),
    option(seed(Seed), Options, 0),
    must_be(integer, Seed),
    (   option(unit(Type), Options) -> must_be(atom, Type), Unit = unit(Type) ; Unit = none ).

output_option(Name, Options, Path) :-
    Opt =.. [Name, Spec],
    (   option(Opt, Options)
    ->  true
    ;   throw(error(ddc_learn(missing_option(Name), learn_split_files/3), _))
    ),
    must_be(text, Spec),
    absolute_file_name(Spec, Path).

check_outputs(Paths, split_settings(Train, Test, _, _, _)) :-
    (   Train == Test -> throw(error(ddc_learn(same_outputs, Train:0), _)) ; true ),
    forall(( member(Out, [Train, Test]), member(Out, Paths) ),
           throw(error(ddc_learn(output_is_input, Out:0), _))),
    forall(( member(Out, [Train, Test]), file_directory_name(Out, Dir),
             \+ exists_directory(Dir) ),
           throw(error(ddc_learn(no_such_directory(Dir), Out:0), _))).

split_data(Data, Paths, Opts, Stats) :-
    Opts = split_settings(Train, Test, F, Seed, Unit),
    data_units(Data, Paths, Unit, Items, NF, Facts, Graph),
    Graph = graph(NU, _),
    choose_test_units(Graph, NF, F, Seed, InTest, K),
    fact_sides(Facts, Graph, InTest, Sides),
    side_counts(Sides, NF, NTrain, NTest, NCut),
    aggregate_all(count, member(split_item(_, _, _, fact0), Items), NBoth),
    Stats = _{train: NTrain, test: NTest, cut: NCut, units: NU, test_units: K, both: NBoth},
    unit_how(Unit, How),
    format(atom(Settings), '~w, fraction ~w, seed ~w', [How, F, Seed]),
    write_parts(Items, Sides, Paths, Train-Test, Settings, Stats).

%   data_units(+Data, +Paths, +Unit, -Items, -NF, -Facts, -Graph): the
%   items of the files (classified, the facts numbered 1..NF), the facts'
%   constants and their units (units/5).
data_units(Data, Paths, Unit, Items, NF, Facts, Graph) :-
    maplist(file_dialect(Data), Paths, Dialects),
    same_dialect(Paths, Dialects),
    check_unit_type(Data, Paths, Unit),
    maplist(read_items, Paths, Dialects, ItemLists),
    foldl(rule_preds(Data), ItemLists, Dialects, [], RPs0),
    sort(RPs0, RulePreds),
    maplist(classify_items(Data, Unit, RulePreds), ItemLists, Dialects, ClassLists),
    append(ClassLists, Items0),
    number_facts(Items0, 0, NF, Items, Facts),
    (   memberchk(split_item(_, _, FirstWhere, fact(_)), Items)
    ->  true
    ;   Paths = [P0|_], throw(error(ddc_learn(no_facts, P0:0), _))
    ),
    units(Facts, NF, Unit, ctx(Data, FirstWhere), Graph).

unit_how(unit(Type), How) :- !, format(atom(How), 'unit ~w', [Type]).
unit_how(none, 'connected worlds').

%!  learn_fold_files(+Files:list, +Options:list, -Stats:list(dict)) is det.
%
%   Split the data of Files into K folds for cross-validation and write,
%   for each fold, a test file (the fold's units) and a training file (the
%   other folds' units).  The units are those of learn_split_files/3; they
%   are shuffled with the seed and dealt out one at a time, each to the
%   fold that holds the fewest facts so far (the first such fold on a
%   tie), so that the folds' test files partition the units and hold about
%   the same number of facts.  Facts whose constants fall in two folds are
%   cut in those two folds (in neither part) and train the others.
%   Options:
%
%     - parts(+Pairs): Train-Test file pairs, one per fold (at least 2;
%       created or replaced, each pair only once both are complete).
%     - seed(+S): the seed of the units' order (default 0).
%     - unit(+Type): split by the constants of that argument type.
%
%   Stats holds per fold `_{fold: I, train: NTrain, test: NTest, cut:
%   NCut, units: NUnits, test_units: K, both: NBoth}`, as
%   learn_split_files/3 counts them.
%
%   @error ddc_learn(Cause, File:Line) as learn_split_files/3, and
%          too_few_units(NUnits, K) when there are fewer units than folds.
%   @error domain_error(at_least_two_folds, Pairs) for fewer than 2 pairs.
learn_fold_files(Files, Options, Stats) :-
    must_be(list, Files),
    must_be(list, Options),
    (   Files == [] -> domain_error(non_empty_list, Files) ; true ),
    (   option(parts(Pairs0), Options)
    ->  must_be(list, Pairs0)
    ;   throw(error(ddc_learn(missing_option(parts), learn_fold_files/3), _))
    ),
    (   Pairs0 = [_, _|_] -> true ; domain_error(at_least_two_folds, Pairs0) ),
    maplist(fold_pair, Pairs0, Pairs),
    option(seed(Seed), Options, 0),
    must_be(integer, Seed),
    (   option(unit(Type), Options) -> must_be(atom, Type), Unit = unit(Type) ; Unit = none ),
    maplist(ddc_learn_data:resolve_data_file, Files, Paths),
    forall(member(Tr-Te, Pairs), check_outputs(Paths, split_settings(Tr, Te, _, _, _))),
    setup_call_cleanup(learn_data_load(Paths, [targets(false)], Data),
                       fold_data(Data, Paths, Pairs, Seed, Unit, Stats),
                       learn_data_free(Data)).

fold_pair(Pair, Train-Test) :-
    (   Pair = Tr0-Te0 -> true ; type_error(pair, Pair) ),
    must_be(text, Tr0),
    must_be(text, Te0),
    absolute_file_name(Tr0, Train),
    absolute_file_name(Te0, Test).

fold_data(Data, Paths, Pairs, Seed, Unit, Stats) :-
    data_units(Data, Paths, Unit, Items, NF, Facts, Graph),
    Graph = graph(NU, FU),
    length(Pairs, K),
    (   NU < K
    ->  Paths = [P0|_],
        throw(error(ddc_learn(too_few_units(NU, K), P0:0), _))
    ;   true
    ),
    deal_units(FU, NF, NU, K, Seed, FoldOf),
    aggregate_all(count, member(split_item(_, _, _, fact0), Items), NBoth),
    unit_how(Unit, How),
    numlist(1, K, Is),
    maplist(write_fold(Items, Facts, Graph, FoldOf, Paths, How, K, Seed, NF, NBoth),
            Is, Pairs, Stats).

%   deal_units(+FU, +NF, +NU, +K, +Seed, -FoldOf): FoldOf (argument U: the
%   fold of unit U), the units taken in the seeded random order, each to
%   the fold with the fewest facts (of that unit alone) so far.
deal_units(FU, NF, NU, K, Seed, FoldOf) :-
    unit_weights(FU, NF, NU, Single, _),
    numlist(1, NU, Us),
    set_random(seed(Seed)),
    random_permutation(Us, Perm),
    functor(FoldOf, fold_of, NU),
    length(Load0, K), maplist(=(0), Load0),
    foldl(deal_unit(Single, FoldOf), Perm, Load0, _).

deal_unit(Single, FoldOf, U, Load0, Load) :-
    min_list(Load0, Min),
    nth1(I, Load0, Min), !,
    arg(U, FoldOf, I),
    arg(U, Single, N),
    New is Min+N,
    nth1(I, Load0, _, Rest),
    nth1(I, Load, New, Rest).

write_fold(Items, Facts, Graph, FoldOf, Paths, How, K, Seed, NF, NBoth, I, Train-Test,
           Stats) :-
    Graph = graph(NU, _),
    functor(InTest, in_test, NU),
    forall(( between(1, NU, U), arg(U, FoldOf, I) ), nb_setarg(U, InTest, true)),
    aggregate_all(count, ( between(1, NU, U), arg(U, FoldOf, I) ), KI),
    fact_sides(Facts, Graph, InTest, Sides),
    side_counts(Sides, NF, NTrain, NTest, NCut),
    Stats = _{fold: I, train: NTrain, test: NTest, cut: NCut, units: NU, test_units: KI,
              both: NBoth},
    format(atom(Settings), '~w, fold ~w of ~w, seed ~w', [How, I, K, Seed]),
    write_parts(Items, Sides, Paths, Train-Test, Settings, Stats).

file_dialect(Data, Path, Dialect) :-
    (   Data:'$ddcl_file'(Path, D) -> Dialect = D ; Dialect = own ).

same_dialect([P|Ps], [D|Ds]) :-
    (   nth1(I, Ds, D2), D2 \== D
    ->  nth1(I, Ps, P2),
        throw(error(ddc_learn(mixed_dialects(P, D, P2, D2), P2:0), _))
    ;   true
    ).

%   check_unit_type(+Data, +Paths, +Unit): Unit is none or unit(Type) of a
%   declared argument type.
check_unit_type(_, _, none) :- !.
check_unit_type(Data, [P|_], unit(Type)) :-
    data_types(Data, Types),
    (   memberchk(Type, Types) -> true
    ;   throw(error(ddc_learn(unknown_unit_type(Type, Types), P:0), _))
    ).

%   data_types(+Data, -Types): the argument types of the data's keys (not
%   DreaML's value types), sorted.
data_types(Data, Types) :-
    findall(T, ( Data:'$ddcl_type'(_, _, KTs, _, _), member(T, KTs), atomic(T) ), Ts),
    sort(Ts, Types).

                 /*******************************
                 *             ITEMS            *
                 *******************************/

read_items(Path, Dialect, Items) :-
    data_read_terms(Path, Dialect, Items).

%   rule_preds(+Data, +Items, +Dialect, +RPs0, -RPs): the predicates
%   (Name/Arity, internal names) that the data define by Prolog rules
%   (H :- B) or non-ground Prolog clauses (not DC clauses).  Their ground clauses (DreaML's
%   `list2set([], [])`) belong to that background definition: they are
%   not facts.
rule_preds(Data, Items, Dialect, RPs0, RPs) :-
    findall(PI, ( member(item(T, _, _, _), Items), rule_pred(Dialect, Data, T, PI) ), New),
    append(New, RPs0, RPs).

rule_pred(Dialect, Data, T, N/A) :-
    nonvar(T),
    (   T = (H :- _) -> true
    ;   \+ ground(T), callable(T), \+ clause_form(T), \+ bias(Dialect, T) -> H = T
    ),
    callable(H),
    catch(internal_key(Data, H, IH), error(ddc_learn(_, _), _), fail),
    functor(IH, N, A).

bias(own, T) :- own_bias(T).
bias(dreaml, T) :- dreaml_bias(T).

%   classify_items(+Data, +Unit, +RulePreds, +Items, +Dialect, -Classified):
%   split_item(Term, VarNames, Where, Class) per item; Class is other,
%   fact0 (a fact without constants) or fact(Consts), Consts a list of
%   Constant-IsUnit.
classify_items(Data, Unit, RulePreds, Items, Dialect, Classified) :-
    maplist(classify(Data, Dialect, Unit, RulePreds), Items, Classified).

classify(Data, Dialect, Unit, RulePreds, item(T, Vs, _, W), split_item(T, Vs, W, Class)) :-
    (   fact_key(Dialect, Data, T, N, KeyArgs),
        \+ rule_fact(Dialect, Data, T, RulePreds)
    ->  key_constants(Data, Unit, N, KeyArgs, Cs),
        ( Cs == [] -> Class = fact0 ; Class = fact(Cs) )
    ;   Class = other
    ).

%   rule_fact(+Dialect, +Data, +Term, +RulePreds): Term is a ground clause
%   of a predicate defined by rules.
rule_fact(Dialect, Data, T, RulePreds) :-
    (   Dialect == own, T = (H := _) -> true ; H = T ),
    \+ clause_form(H),
    internal_key(Data, H, IH),
    functor(IH, N, A),
    ord_memberchk(N/A, RulePreds).

%   fact_key(+Dialect, +Data, +Term, -Name, -KeyArgs) is semidet: Term is
%   a fact whose key (internal form) is Name(KeyArgs...).
fact_key(own, Data, T, N, KeyArgs) :-
    own_fact_key(T, K),
    internal_key(Data, K, IK),
    IK =.. [N|KeyArgs].
fact_key(dreaml, Data, T, N, KeyArgs) :-
    ground(T), callable(T),
    \+ clause_form(T),
    \+ dreaml_bias(T),
    T =.. [N|As],
    length(As, A),
    (   A > 0, A1 is A-1, learn_data_pred(Data, N, A1, rv(_))
    ->  append(KeyArgs, [_], As)
    ;   KeyArgs = As
    ).

own_fact_key(T, _) :- var(T), !, fail.
own_fact_key(K ~= V, K) :- !, ground(K), ground(V), callable(K).
own_fact_key(K ~ _, K) :- !, ground(K), callable(K).
own_fact_key(P :: A, A) :- !, number(P), ground(A), callable(A).
own_fact_key((H := B), H) :- !, B == true, ground(H), callable(H), \+ clause_form(H).
own_fact_key(A, A) :-
    ground(A), callable(A),
    \+ clause_form(A),
    \+ own_bias(A).

%   clause_form(+T): T is a directive, a rule or a DC form, not an atom.
clause_form(T) :-
    compound(T),
    functor(T, N, Ar),
    memberchk(N/Ar, [(:-)/1, (:-)/2, (:=)/2, (<-)/2, (~)/2, (~=)/2, (::)/2, (pr)/2, (?-)/1]).

%   own_bias(+T), dreaml_bias(+T): T is a declaration of the bias
%   (bias_term/2), written to both parts; a weight(Key, W) is not one here:
%   it is split with the facts.
own_bias(T) :- bias_term(own, T), T \= weight(_, _).

dreaml_bias(T) :- bias_term(dreaml, T).

%   key_constants(+Data, +Unit, +Name, +KeyArgs, -Consts): the atomic key
%   arguments, each with true when it stands in a position of the type of
%   Unit = unit(Type) (false for Unit = none).
key_constants(Data, Unit, N, KeyArgs, Cs) :-
    length(KeyArgs, KA),
    (   Unit = unit(Type), Data:'$ddcl_type'(N, KA, Types, _, _)
    ->  true
    ;   length(Types, KA)
    ),
    foldl(key_constant(Type), KeyArgs, Types, Cs, []).

key_constant(UnitType, A, T, Cs0, Cs) :-
    (   atomic(A)
    ->  ( nonvar(T), T == UnitType -> IsUnit = true ; IsUnit = false ),
        Cs0 = [A-IsUnit|Cs]
    ;   Cs0 = Cs
    ).

%   number_facts(+Items0, +N0, -N, -Items, -Facts): the facts with
%   constants get ids N0+1..N: their class becomes fact(Id-Consts); Facts
%   is the list of their Consts, in order.
number_facts([], N, N, [], []).
number_facts([I0|Is0], N0, N, [I|Is], Fs) :-
    I0 = split_item(T, Vs, W, C0),
    (   C0 = fact(Cs)
    ->  N1 is N0+1, I = split_item(T, Vs, W, fact(N1-Cs)), Fs = [Cs|Fs1]
    ;   N1 = N0, I = I0, Fs = Fs1
    ),
    number_facts(Is0, N1, N, Is, Fs1).

                 /*******************************
                 *             UNITS            *
                 *******************************/

%   units(+Facts, +NF, +Unit, +Ctx, -Graph): Graph is graph(NU, FactUnits):
%   the number of units and, per fact id, the sorted list of the units of
%   its constants (a compound, argument Id).  Ctx is ctx(Data, Where),
%   Where the first fact's File:Line (for errors about the facts as a
%   whole).
%
%   Constants get ids 1..NC in the order they first appear; CF (argument C:
%   the ids of the facts of constant C, in order) and FC (argument F: the
%   constant ids of fact F) are the bipartite fact-constant graph; Own
%   (argument C: Unit-Distance of constant C) and Seen (argument F: bound
%   once fact F is entered) start unbound.
units(Facts, NF, Unit, ctx(Data, W), graph(NU, FU)) :-
    empty_assoc(A0),
    foldl(intern_fact, Facts, FIds, s(A0, 0, []), s(Assoc, NC, UnitIds0)),
    FC =.. [fc|FIds],
    findall(C-F, ( nth1(F, FIds, Cs), member(C, Cs) ), CFPairs0),
    keysort(CFPairs0, CFPairs),
    group_pairs_by_key(CFPairs, Grouped),
    pairs_values(Grouped, CFLists),
    CF =.. [cf|CFLists],
    functor(Own, own, NC),
    functor(Seen, seen, NF),
    G = g(CF, FC, Own, Seen),
    sort(UnitIds0, UnitIds),
    (   Unit == none
    ->  components(1, NC, G, 0, NU)
    ;   Unit = unit(Type),
        UnitIds == []
    ->  throw(error(ddc_learn(no_unit_constants(Type), W), _))
    ;   Unit = unit(Type),
        UnitIds = [U1]
    ->  assoc_to_list(Assoc, CIs), memberchk(UC-U1, CIs),
        throw(error(ddc_learn(one_unit(Type, UC), W), _))
    ;   foldl(source(Own), UnitIds, 0, NU0),
        bfs(UnitIds, 0, G),
        components(1, NC, G, NU0, NU)
    ),
    (   NU < 2
    ->  data_types(Data, Types),
        throw(error(ddc_learn(one_world(Types), W), _))
    ;   true
    ),
    length(FIds, NF),
    maplist(fact_units(Own), FIds, FUs),
    FU =.. [fu|FUs].

intern_fact(Cs, Ids, S0, S) :-
    foldl(intern, Cs, Ids0, S0, S),
    sort(Ids0, Ids).

intern(C-IsUnit, Id, s(A0, N0, U0), s(A, N, U)) :-
    (   get_assoc(C, A0, Id0)
    ->  Id = Id0, A = A0, N = N0
    ;   N is N0+1, Id = N, put_assoc(C, A0, Id, A)
    ),
    (   IsUnit == true -> U = [Id|U0] ; U = U0 ).

source(Own, C, U0, U) :-
    U is U0+1,
    arg(C, Own, U-0).

%   components(+C, +NC, +G, +U0, -U): every constant C.. that no unit owns
%   yet starts a unit of its own: its connected component.
components(C, NC, G, U0, U) :-
    (   C > NC
    ->  U = U0
    ;   G = g(_, _, Own, _),
        arg(C, Own, O),
        (   var(O)
        ->  U1 is U0+1, O = U1-0,
            bfs([C], 0, G)
        ;   U1 = U0
        ),
        C1 is C+1,
        components(C1, NC, G, U1, U)
    ).

%   bfs(+Frontier, +Level, +G): breadth-first, one level at a time, from
%   the constants of Frontier (owned by their units at distance Level).
%   The facts of the frontier not entered yet are taken in the data's
%   order; each gives its constants that no unit owns yet the unit of its
%   first constant of the frontier, at distance Level+1: a constant
%   equally near two units goes to the one the first such fact reaches it
%   from.  Owned constants (another unit's included) are not entered
%   again.
bfs([], _, _) :- !.
bfs(Frontier, L, G) :-
    G = g(CF, _, _, Seen),
    findall(F, ( member(C, Frontier), arg(C, CF, Fs), member(F, Fs),
                 arg(F, Seen, S), var(S) ),
            Fs0),
    sort(Fs0, Fs1),
    L1 is L+1,
    foldl(enter_fact(G, L, L1), Fs1, Next, []),
    bfs(Next, L1, G).

enter_fact(G, L, L1, F, Next0, Next) :-
    G = g(_, FC, Own, Seen),
    arg(F, Seen, S),
    (   nonvar(S)
    ->  Next0 = Next
    ;   S = true,
        arg(F, FC, Cs),
        once(( member(C, Cs), arg(C, Own, O), nonvar(O), O = U-L )),
        enqueue(Cs, U-L1, Own, Next0, Next)
    ).

enqueue([], _, _, T, T).
enqueue([C|Cs], UL, Own, T0, T) :-
    arg(C, Own, O),
    (   var(O) -> O = UL, T0 = [C|T1] ; T1 = T0 ),
    enqueue(Cs, UL, Own, T1, T).

fact_units(Own, Cs, Us) :-
    maplist(owner(Own), Cs, Us0),
    sort(Us0, Us).

owner(Own, C, U) :- arg(C, Own, U-_).

                 /*******************************
                 *          TEST UNITS          *
                 *******************************/

%   choose_test_units(+Graph, +NF, +F, +Seed, -InTest, -K): InTest
%   (argument U: bound iff unit U is a test unit) after adding units in the
%   seeded random order until the test facts are at least F*NF.
choose_test_units(graph(NU, FU), NF, F, Seed, InTest, K) :-
    unit_weights(FU, NF, NU, Single, Multi),
    numlist(1, NU, Us),
    set_random(seed(Seed)),
    random_permutation(Us, Perm),
    functor(InTest, in_test, NU),
    Goal is F*NF,
    MaxK is NU-1,
    add_units(Perm, Single, Multi, InTest, Goal, MaxK, 0, 0, K).

add_units([U|Us], Single, Multi, InTest, Goal, MaxK, K0, N0, K) :-
    (   K0 >= 1, ( N0 >= Goal ; K0 >= MaxK )
    ->  K = K0
    ;   arg(U, InTest, true),
        arg(U, Single, NS),
        arg(U, Multi, Ms),
        aggregate_all(count, ( member(FUs, Ms), all_test(FUs, InTest) ), NM),
        N1 is N0+NS+NM,
        K1 is K0+1,
        add_units(Us, Single, Multi, InTest, Goal, MaxK, K1, N1, K)
    ).

all_test(Us, InTest) :-
    forall(member(U, Us), ( arg(U, InTest, X), nonvar(X) )).

no_test(Us, InTest) :-
    forall(member(U, Us), ( arg(U, InTest, X), var(X) )).

%   unit_weights(+FU, +NF, +NU, -Single, -Multi): Single (argument U: the
%   facts all of whose constants are in U) and Multi (argument U: the unit
%   lists of the facts that span U and other units).
unit_weights(FU, NF, NU, Single, Multi) :-
    findall(U, ( between(1, NF, F), arg(F, FU, [U]) ), Ones0),
    msort(Ones0, Ones),
    clumped(Ones, Counts),
    length(SL, NU), maplist(=(0), SL),
    Single =.. [single|SL],
    forall(member(U-N, Counts), nb_setarg(U, Single, N)),
    findall(U-Us, ( between(1, NF, F), arg(F, FU, Us), Us = [_, _|_], member(U, Us) ), MP0),
    keysort(MP0, MP),
    group_pairs_by_key(MP, MG),
    length(ML, NU), maplist(=([]), ML),
    Multi =.. [multi|ML],
    forall(member(U-L, MG), nb_setarg(U, Multi, L)).

%   fact_sides(+Facts, +Graph, +InTest, -Sides): Sides (argument F: train,
%   test or cut).
fact_sides(Facts, graph(_, FU), InTest, Sides) :-
    length(Facts, NF),
    functor(Sides, sides, NF),
    forall(between(1, NF, F),
           ( arg(F, FU, Us),
             (   all_test(Us, InTest) -> S = test
             ;   no_test(Us, InTest) -> S = train
             ;   S = cut
             ),
             nb_setarg(F, Sides, S) )).

side_counts(Sides, NF, NTrain, NTest, NCut) :-
    aggregate_all(count, ( between(1, NF, F), arg(F, Sides, train) ), NTrain),
    aggregate_all(count, ( between(1, NF, F), arg(F, Sides, test) ), NTest),
    aggregate_all(count, ( between(1, NF, F), arg(F, Sides, cut) ), NCut).

                 /*******************************
                 *            WRITING           *
                 *******************************/

write_parts(Items, Sides, Paths, Train-Test, Settings, Stats) :-
    tmp_name(Train, TrainTmp),
    tmp_name(Test, TestTmp),
    maplist(file_base_name, Paths, Bases),
    atomic_list_concat(Bases, ', ', Inputs),
    setup_call_catcher_cleanup(
        true,
        ( write_part(TrainTmp, train, Items, Sides,
                     header('Training', Inputs, Settings, Stats.train, Stats)),
          write_part(TestTmp, test, Items, Sides,
                     header('Test', Inputs, Settings, Stats.test, Stats)),
          rename_file(TrainTmp, Train),
          rename_file(TestTmp, Test) ),
        Catcher,
        (   Catcher == exit -> true
        ;   forall(member(Tmp, [TrainTmp, TestTmp]),
                   ( exists_file(Tmp) -> catch(delete_file(Tmp), _, true) ; true ))
        )).

tmp_name(Path, Tmp) :-
    file_directory_name(Path, Dir),
    file_base_name(Path, Base),
    current_prolog_flag(pid, Pid),
    format(atom(Tmp), '~w/.~w.~w.tmp', [Dir, Base, Pid]).

write_part(File, Side, Items, Sides, Header) :-
    setup_call_cleanup(open(File, write, S, [encoding(utf8)]),
                       ( write_header(S, Header),
                         forall(( member(split_item(T, Vs, _, C), Items), on_side(C, Side, Sides) ),
                                write_item(S, T, Vs)) ),
                       close(S)).

on_side(other, _, _).
on_side(fact0, _, _).
on_side(fact(F-_), Side, Sides) :- arg(F, Sides, Side).

write_header(S, header(Part, Inputs, Settings, N, St)) :-
    format(S, '% ~w part of ~w, split by ddc split (~w): ~D facts.~n',
           [Part, Inputs, Settings, N]),
    format(S, '% ~D units, ~D of them in the test part; ~D facts in the training part, ~D in the test part,~n',
           [St.units, St.test_units, St.train, St.test]),
    format(S, '% ~D cut (their constants on both sides: in neither part), ~D without constants (in both).~n',
           [St.cut, St.both]),
    format(S, '% Declarations, directives and rules are in both parts.~n~n', []).

%   write_item(+Stream, +Term, +VarNames): Term as a clause the data reader
%   reads back to the same term: variables by their names ('_' for the
%   anonymous ones), the DC operators.
write_item(S, T, Vs) :-
    \+ \+ ( maplist(bind_var_name, Vs),
            term_variables(T, Anon),
            maplist(=('$VAR'('_')), Anon),
            write_term(S, T, [ quoted(true), numbervars(true), ignore_ops(false),
                               module(ddc_learn_data), spacing(next_argument),
                               fullstop(true), nl(true) ]) ).

bind_var_name(Name=V) :-
    (   var(V) -> V = '$VAR'(Name) ; true ).

                 /*******************************
                 *            MESSAGES          *
                 *******************************/

%   The data reader's prolog:message//1 clause for error(ddc_learn(Cause,
%   Where), _) renders causes it does not know with ~q, and it is loaded
%   first; prolog:message//2 (the message's language) is consulted before
%   prolog:message//1, so this module's causes get their text there.

:- multifile prolog:message//2.

prolog:message(_Lang, error(ddc_learn(Cause, Where), _)) -->
    { nonvar(Cause) },
    split_message(Cause, Where).

split_message(Cause, Where) -->
    ddc_learn_messages:learn_where(Where),
    split_cause(Cause).

split_cause(one_world(Types)) --> !,
    [ 'the facts form one connected world: no part of it can be held out; ' ],
    (   { Types == [] }
    ->  [ 'declare argument types (type/1) and split by one with unit(Type) (ddc split --unit TYPE)' ]
    ;   { atomic_list_concat(Types, ', ', TypesText) },
        [ 'split by the constants of a type with unit(Type) (ddc split --unit TYPE), one of: ~w'-[TypesText] ]
    ).
split_cause(unknown_unit_type(Type, Types)) --> !,
    (   { Types == [] }
    ->  [ 'unknown unit type ~q: the data declare no argument types (type/1, base/1)'-[Type] ]
    ;   { atomic_list_concat(Types, ', ', TypesText) },
        [ 'unknown unit type ~q: the data''s argument types are ~w'-[Type, TypesText] ]
    ).
split_cause(one_unit(Type, C)) --> !,
    [ 'only one constant of type ~w (~q): no unit can be held out'-[Type, C] ].
split_cause(no_unit_constants(Type)) --> !,
    [ 'no fact has a constant of type ~w: no units to split by'-[Type] ].
split_cause(too_few_units(NU, K)) --> !,
    [ 'the facts form ~D units (separate worlds), fewer than the ~D folds asked for'-[NU, K] ].
split_cause(no_facts) --> !,
    [ 'no facts with constants to split' ].
split_cause(mixed_dialects(F1, D1, _, D2)) --> !,
    { dialect_name(D1, N1), dialect_name(D2, N2) },
    [ 'this file is in ~w dialect and ~w in ~w: one output file could not hold both'-[N2, F1, N1] ].
split_cause(output_is_input) --> !,
    [ 'an output of the split is an input file: it would be overwritten' ].
split_cause(no_such_directory(Dir)) --> !,
    [ 'no such directory: ~w'-[Dir] ].
split_cause(missing_option(Name)) --> !,
    [ 'the option ~w(File) is required'-[Name] ].
split_cause(same_outputs) --> !,
    [ 'the training and the test part would be the same file' ].

dialect_name(own, 'the project''s own').
dialect_name(dreaml, 'DreaML''s').
