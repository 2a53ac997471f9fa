/*  ddc.pl -- Dynamic Distributional Clauses for SWI-Prolog.

    The engine of the project: the DC language of section 2.2 of the paper
    (distributional clauses, derived atoms, time-indexed terms), compiled
    into Prolog, with likelihood-weighted backward sampling for static
    queries and (in ddc_filter.pl, re-exported here) the particle filter
    over time.
*/

:- module(ddc,
          [ ddc_load/1,                 % +File
            ddc_load/2,                 % +File, ?Module
            ddc_program/1,              % -Module (the program loaded last)
            query/2,                    % :Query, -P
            query/3,                    % :Query, -P, +Options
            query/4,                    % +Evidence, :Query, -P, +Options
            query/5,                    % +PosEv, +NegEv, +Query, +N, -P
            query/8,                    % +PosEv, +NegEv, +Query, ?X, +N, -Avg, -SuccSum, -Sum
            expectation/5,              % +Evidence, +Query, ?X, -E, +Options
            distribution/5,             % +Evidence, +Query, ?X, -Dist, +Options
            ddc_query/6,                % +Module, +Evidence, +Query, +Options, -P, -Stats
            ddc_query_text/6,           % +Module, +QueryText, +EvidenceText, +N, +Seed, -Result
            ddc_expectation_text/7,     % +Module, +ValueText, +QueryText, +EvidenceText, +N, +Seed, -Result
            ddc_distribution_text/7,    % +Module, +ValueText, +QueryText, +EvidenceText, +N, +Seed, -Pairs
            ddc_sample_world/4,         % +Module, +Query, +Options, -Facts
            filter_new/4,               % +ProgramFile, +N, +Seed, -Filter
            filter_new/5,               % +ProgramFile, +N, +Seed, +Options, -Filter
            filter_step/4,              % +Filter, +Observations, +Actions, -LogWeights
            filter_undo/1,              % +Filter
            filter_resample/2,          % +Filter, +Indices
            filter_holds/3,             % +Filter, +Goal, -Flags
            filter_values/4,            % +Filter, +Template, +Goal, -Values
            filter_rows/6,              % +Filter, +Template, +Goal, -Width, -Floats, -Values
            filter_time/2,              % +Filter, -T
            filter_engine/2,            % +Filter, -Engine
            filter_size/2,              % +Filter, -N
            filter_statistics/2,        % +Filter, -Stats
            filter_free/1,              % +Filter
            op(700, xfx, ~),
            op(700, xfx, ~=),
            op(1105, xfx, :=),
            op(1105, xfx, <-),
            op(1150, xfx, pr)
          ]).

:- use_module(library(lists)).
:- use_module(library(apply)).
:- use_module(library(aggregate)).
:- use_module(library(option)).
:- use_module(library(error)).
:- use_module(library(pairs)).
:- use_module(library(assoc)).
:- use_module(library(ordsets)).
:- use_module(library(modules)).
:- use_module(ddc_dist).
:- use_module(ddc_store).
:- use_module(ddc_batch).
:- use_module(ddc_nesting).
:- use_module(dc_compat_load).   % the original DC's option directives and arithmetic
:- reexport(ddc_models).       % logistic/3, linear/3, softmax/3, mean_list/2, ...

:- op(700, xfx, ~).
:- op(700, xfx, ~=).
:- op(1105, xfx, :=).
:- op(1105, xfx, <-).
:- op(1150, xfx, pr).

%   Arithmetic compiled to virtual-machine instructions instead of calls to
%   is/2 and friends (the flag is local to this file): about a fifth fewer
%   instructions per sample.  Program clauses are asserted the same way
%   (optimised/1).
:- set_prolog_flag(optimise, true).

/** <module> Dynamic Distributional Clauses

## API (final signatures)

  - ddc_load(+File), ddc_load(+File, ?Module), ddc_program(-Module)
  - query(+Query, -P), query(+Query, -P, +Options),
    query(+Evidence, +Query, -P, +Options), query(+PosEv, +NegEv, +Query, +N, -P),
    query(+PosEv, +NegEv, +Query, ?X, +N, -Avg, -SuccSum, -Sum),
    expectation(+Evidence, +Query, ?X, -E, +Options),
    distribution(+Evidence, +Query, ?X, -Dist, +Options),
    ddc_query(+Module, +Evidence, +Query, +Options, -P, -stats(SE, ESS, NCounted, N))
  - Python bridge helpers: ddc_query_text/6, ddc_expectation_text/7, ddc_distribution_text/7
  - logistic(+Inputs, +Weights, -P), linear(+Inputs, +Weights, -Y),
    softmax(+Inputs, +WeightRows, -Ps), mean_list/2, mode_list/2,
    antimode_list/2 (ddc_models.pl, re-exported)
  - Particle filter (ddc_filter.pl): filter_new(+ProgramFile, +N, +Seed, -Filter),
    filter_step(+Filter, +Observations, +Actions, -LogWeights), filter_undo(+Filter),
    filter_resample(+Filter, +Indices), filter_holds(+Filter, +Goal, -Flags),
    filter_values(+Filter, +Template, +Goal, -Values), filter_time(+Filter, -T),
    filter_engine(+Filter, -Engine),
    filter_size(+Filter, -N), filter_statistics(+Filter, -Stats), filter_free(+Filter);
    filter_new(+ProgramFile, +N, +Seed, +Options, -Filter) with share(false) computes
    every value in every particle (see "Shared values" below), threads(K) steps the
    particles in K threads, engine(auto|batched|per_particle) picks the engine: the
    batched one (ddc_batch.pl, each clause evaluated once for a batch of particles) for
    a program in its fragment, by default

## Loading

    ?- ddc_load('prolog/examples/tutorial.pl'), query(coin ~= true, P).

ddc_load/1 reads a program file and compiles it into a module of its own
(named after the absolute file name; ddc_load/2 names it).  Several
programs live side by side; loading a file again replaces its program
atomically: if the new text has an error, the exception names file:line and
the previously loaded program stays as it was.  Loads run one at a time
(load_program/2); a filter compiles its program into a module of its own
that no later load replaces (filter_new/5).  A Prolog file may also load
a program as a directive: `:- use_module(library(ddc)). :- ddc_load(model).`

## Language

  - `H ~ D := Body.`, `H ~ D.`, `H := Body.` (`H := true.` is a fact); the
    paper's `<-` is a synonym of `:=`; a trailing `pr N` is accepted and
    ignored (priorities only matter to forward samplers).
  - Time: `h:t`, `h:t+1`, `h:0` (also `h:N`) in heads and bodies; the
    original's `current(h)`, `next(h)`, `prior(h)` mean the same.
  - Body literals: `H ~= V`, derived atoms, `\+ G`, `(A;B)`, `(A->B;C)`,
    Prolog builtins and library(lists) predicates, findall/3 (its goal may
    use DC literals), findall_forward/3 (same), true(P) (a fresh flip at
    each call), sample(D, X) (inline draw), belief(A) (A is ground),
    timestep(T), the models and aggregates of learned clauses (logistic/3,
    linear/3, softmax/3, mean_list/2, mode_list/2, antimode_list/2:
    ddc_models.pl), predicates declared with
    `builtin(Pattern).` or defined by plain Prolog clauses in the program
    file.  A predicate with no clauses at all is looked up among the facts
    asserted into the world (actions and plain observations of the filter).
  - Comparisons accept a time-indexed random variable as an operand:
    `pos(1):t > 0` reads pos(1) at t first (the paper's shorthand).
  - Distribution sugar: `finite(P:V, ...)` (no list), `uniform(A, B)`
    (= contUniform(A, B), the paper's notation).  Parameters may be
    arithmetic expressions (`gaussian(X+3, 0.5)`).

## Semantics

Each world samples lazily only what the proofs need; every random variable
is drawn at most once per world (the store survives backtracking).  The
first clause (in file order) whose body holds defines a variable; if a
later clause for the same variable also holds in the same world, that is
an error naming both clauses (the original silently took the first), unless
the program declares `:- first_applicable(Name/Arity).` (or
`first_applicable(all)`) for decision lists such as learned rules.
Time-indexed variables: `h:0` and `h:t+1` clauses define h at time 0 /
t+1; `h:t` clauses are a fallback used only when no `h:0`/`h:t+1` clause
applies (the lazily-drawn "prior belief" of the original).  Nothing is
copied from t to t+1 implicitly: write `h:t+1 ~ val(V) := h:t ~= V` or
declare `:- persistent(Name/Arity).`, which adds exactly that clause
(`h:t+1 := h:t` for a derived atom) after the program's own ones.

Ground derived atoms whose proof uses true/1 or sample/2 are memoised per
world (success and failure), so such an atom has one truth value per world.

## Inference

Likelihood weighting with backward reasoning.  Evidence literals `h ~= v`
with ground h and v are not sampled but weighted by the density or mass of
h's applicable clause; evidence on a `val(V)` variable whose body computes
V by invertible arithmetic from another variable (`V is A*4.0`) is
propagated to that variable with the Jacobian (the original omitted it).
Other evidence (non-ground values, tests, atoms) is by rejection.  Ground
query literals `h ~= v` are weighted the same way (so `query(g ~= 0.0, P)`
on a continuous g returns a density).  As in the original, only samples
whose evidence weight has the fewest density factors count (a point mass
beats a density).

## Errors

Every error is `error(ddc(Cause, Where), _)` with Where = File:Line (or
`query`); print_message/2 renders it as `File:Line: cause`.  Causes:
syntax_error(Msg), distribution(Dist, Why), non_ground_head(H),
overlapping_clauses(Key, OtherFile:OtherLine), zero_evidence(Evidence),
no_observation_clause(Obs), unknown_program(M), bad_directive(D).
*/

:- dynamic
    current_program_/1,
    program_file_/2.

:- multifile prolog:message//1.

                 /*******************************
                 *            LOADING           *
                 *******************************/

%!  ddc_load(+File) is det.
%!  ddc_load(+File, ?Module) is det.
%
%   Compile the DC program in File into Module (default: the absolute file
%   name) and make it the current program for query/2,3,4.  Replaces a
%   previous program of that module only if File compiles without error.
ddc_load(File) :-
    ddc_load(File, _).

ddc_load(Spec, M) :-
    resolve_file(Spec, File),
    (   var(M) -> M = File ; true ),
    with_mutex('$ddc_load',
               (   load_program(File, M),
                   retractall(current_program_(_)),
                   assertz(current_program_(M)) )).

%!  load_program(+File:atom, +Module:atom) is det.
%
%   Reads and compiles the DC program in File (an absolute file name) and
%   installs it into Module, replacing what Module held only if File
%   compiles without error.  Loads run one at a time (mutex '$ddc_load'):
%   two threads loading into one module do not interleave their clauses.
%   A filter's program is loaded into a module of the filter's own
%   (filter_new/5), which no later load replaces.
load_program(File, M) :-
    must_be(atom, File),
    must_be(atom, M),
    with_mutex('$ddc_load',
               (   read_program(File, Items),
                   compile_program(File, M, Items, Clauses, Info),
                   install_program(M, File, Clauses, Info) )).

%!  unload_program(+Module:atom) is det.
%
%   Removes the program loaded into Module (its predicates and its file).
unload_program(M) :-
    must_be(atom, M),
    with_mutex('$ddc_load',
               (   clear_program_module(M),
                   retractall(program_file_(M, _)),
                   retractall(current_program_(M)) )).

resolve_file(Spec, File) :-
    (   absolute_file_name(Spec, File0, [file_type(prolog), access(read), file_errors(fail)])
    ->  File = File0
    ;   absolute_file_name(Spec, File0, [access(read), file_errors(fail)])
    ->  File = File0
    ;   term_to_atom(Spec, A),
        throw(error(ddc(no_such_file(A), A:0), _))
    ).

%!  ddc_program(-Module) is semidet.
%
%   The program loaded last.
ddc_program(M) :-
    current_program_(M), !.

%   program_items(+Module, -Items): the classified items of the program
%   loaded into Module (with the clauses its persistent/1 directives add,
%   and rivals(Id, R) for each random variable clause: whether a later
%   clause can define what it defines, see rivals/7), as the batched filter
%   reads them (ddc_batch.pl); kept by compile_program/5.
program_items(M, Items) :-
    M:'$ddc_items'(Items).

%   read_program(+File, -Items): Items is a list of t(Term, Line).
%
%   The file is read in a temporary module that inherits the engine's
%   operators (its base module is ddc): an `:- op/3` directive of the file
%   applies to the rest of that file, from its line on, and to nothing
%   else, so a program (even one that is refused) cannot change how other
%   programs or queries are read.
read_program(File, Items) :-
    check_file_nesting(File),
    in_temporary_module(Reader,
                        set_module(Reader:base(ddc)),
                        read_program(File, Reader, Items)).

read_program(File, Reader, Items) :-
    setup_call_cleanup(
        open(File, read, S),
        read_terms(S, File, Reader, Items),
        close(S)).

read_terms(S, File, Reader, Items) :-
    catch(read_term(S, T, [ module(Reader), term_position(P), syntax_errors(error) ]),
          E, syntax_error(E, File)),
    (   T == end_of_file
    ->  Items = []
    ;   stream_position_data(line_count, P, Line),
        reader_directive(T, Reader, File:Line),
        Items = [t(T, Line)|Rest],
        read_terms(S, File, Reader, Rest)
    ).

%   reader_directive(+Term, +Reader, +Where): an op/3 directive takes
%   effect in the reading module at once; an error of op/3 (a bad priority
%   or type, redefining `,` or `|`) is the program's error at Where.
reader_directive(T, Reader, Where) :-
    nonvar(T), T = (:- D), nonvar(D), D = op(P, Type, Names), !,
    catch(op(P, Type, Reader:Names), E, load_error(E, op(P, Type, Names), Where)).
reader_directive(_, _, _).

syntax_error(error(syntax_error(Msg), Ctx), File) :- !,
    (   Ctx = stream(_, Line, _, _) -> true
    ;   Ctx = file(_, Line, _, _) -> true
    ;   Line = 0
    ),
    throw(error(ddc(syntax_error(Msg), File:Line), _)).
syntax_error(E, _) :-
    throw(E).

install_program(M, File, Clauses, Info) :-
    clear_program_module(M),
    set_module(M:base(user)),
    set_module(M:class(user)),
    declare_program_preds(M, Info),
    optimised(forall(member(C, Clauses), install_clause(M, C))),
    assertz(M:'$ddc_info'(Info)),
    retractall(program_file_(M, _)),
    assertz(program_file_(M, File)).

%   install_clause(+Module, +Clause): a clause compiled from a line of the
%   program ('$at'(Line, C)) is kept with that line, so that an error at
%   run time names it (program_error/4).
install_clause(M, '$at'(L, C)) :- !,
    assertz(M:C, Ref),
    assertz(M:'$clause_line'(Ref, L)).
install_clause(M, C) :-
    assertz(M:C).

%   clear_program_module(+M): the predicates of a program module gone.
clear_program_module(M) :-
    (   current_module(M), M \== user, M \== ddc, M \== system
    ->  forall(( current_predicate(M:N/A), functor(H, N, A),
                 \+ predicate_property(M:H, imported_from(_)) ),
               abolish(M:N/A))
    ;   true
    ).

%   optimised(:Goal): Goal (asserting clauses) with arithmetic compiled
%   inline, as in this file; the caller's flag is restored.
:- meta_predicate optimised(0).
optimised(Goal) :-
    current_prolog_flag(optimise, Old),
    setup_call_cleanup(set_prolog_flag(optimise, true), Goal,
                       set_prolog_flag(optimise, Old)).

declare_program_preds(M, Info) :-
    Info = info(DerU, DerT, _, _, _, _, _),
    dynamic(M:'$rv'/9),
    dynamic(M:'$rv_pos'/3),
    dynamic(M:'$clause_line'/2),
    dynamic(M:'$ddc_info'/1),
    dynamic(M:'$ddc_items'/1),
    dynamic(M:'$ddc_tmp'/4),
    dynamic(M:'$sweep'/4),
    dynamic(M:'$sweep_key'/4),
    forall(member(N/A, DerU),
           ( A1 is A+1, derived_name(N, d, DN), dynamic(M:DN/A1),
             derived_name(N, d0, DN0), dynamic(M:DN0/A1),
             derived_name(N, ds, DNS), dynamic(M:DNS/A1) )),
    forall(member(N/A, DerT),
           ( A2 is A+2,
             forall(member(K, [dt, dt0, dt1, dt2, dts]),
                    ( derived_name(N, K, DN), dynamic(M:DN/A2) )) )).

derived_name(N, Kind, Name) :-
    atomic_list_concat(['$', Kind, ':', N], Name).

                 /*******************************
                 *          COMPILATION         *
                 *******************************/

%   An item is one of
%     rv(Id, X, Kind, Dist, Body, Line)
%     der(Id, X, Kind, Body, Line)
%     plain(Clause, Line)
%     dir(Directive, Line)
%   Kind is u, state, trans or fixed(N).

compile_program(File, M, Items00, Clauses, Info) :-
    original_program(Items00, Items0),   % `X is random`, logfinite([W:_]) (dc_compat_load.pl)
    retractall(undefined_call_(_, _)),
    classify_items(Items0, File, 1, Items1, Dirs),
    directives_options(Dirs, File, M, Opts, DirClauses),
    add_persistence(Opts, Items1, Items),
    program_info(Items, Opts, Info),
    %   '$rv' clauses: tier 1 (untimed, h:0, h:t+1) before tier 2 (h:t)
    rivals_table(Items, Info, RivalsOf),
    findall(C, ( member(I, Items), \+ state_rv(I), compile_item_at(I, File, Info, RivalsOf, C) ), Cs1),
    findall(C, ( member(I, Items), state_rv(I), compile_item_at(I, File, Info, RivalsOf, C) ), Cs2),
    append(Cs1, Cs2, Cs0),
    derived_dispatchers(M, Info, Ds),
    clause_positions(Items, File, Ps),
    findall(Id-K-C, ( member(rv(Id, X, K, _, B, _), Items), K \== u, K \== state,
                      sweep_key_clause(Id, X, K, B, Info, C) ), SwKs0),
    distinct_sweep_keys(SwKs0, SwKs),
    findall('$sweep'(rv, K, X, Id),
            ( member(Id-K-C, SwKs), C = ('$sweep_key'(_, X, _, _) :- _) ), Sw1a),
    findall(C, member(_-_-C, SwKs), Sw1b),
    append(Sw1a, Sw1b, Sw1),
    Info = info(_, _, _, _, _, Impure, _),
    %   '$sweep'(der, Kind, N/A, sw(Shared, When, G, Call, T, W)): Call (the
    %   h:t+1 clauses of derived predicate N/A) gives the instances G at T
    %   in W; When is eager (materialised by the sweep: the program reads
    %   N/A at a time other than t+1) or lazy (on first demand, '$mat'/3)
    findall(K-N/A, ( member(der(_, X, K, _, _), Items), K \== u, K \== state,
                     functor(X, N, A) ), DKs0),
    sort(DKs0, DKs),
    lookback_preds(Items, Back),
    findall('$sweep'(der, K, N/A, sw(Sh, When, G, H1, T, W)),
            ( member(K-N/A, DKs),
              ( memberchk(clean(t/N/A), Impure) -> Sh = shared ; Sh = 0 ),
              ( memberchk(N/A, Back) -> When = eager ; When = lazy ),
              functor(G, N, A), G =.. [_|Args],
              derived_name(N, dt1, DN1), append(Args, [T, W], CArgs), H1 =.. [DN1|CArgs] ),
            Sw2a),
    sort(Sw2a, Sw2),
    findall(rivals(Id, R), ( member(rv(Id, _, _, _, _, _), Items), rivals(Id, RivalsOf, R) ), Rivals),
    append(Items, Rivals, BatchItems),
    append([DirClauses, Cs0, Ds, Ps, Sw1, Sw2, ['$ddc_items'(BatchItems)]], Clauses),
    b_setval(ddc_compiling, []),
    warn_undefined.

state_rv(rv(_, _, state, _, _, _)).

%   lookback_preds(+Items, -Preds): the N/A read in some body at a time
%   other than t+1 (t, t-K, a number, a variable, current/prior), i.e.
%   possibly at a frozen time by the program itself.
lookback_preds(Items, Preds) :-
    findall(N/A, ( member(I, Items),
                   ( I = rv(_, _, _, _, B, _) ; I = der(_, _, _, B, _) ),
                   time_ref(B, X, TE), \+ next_time(TE),
                   callable(X), functor(X, N, A) ), L),
    sort(L, Preds).

next_time(TE) :- nonvar(TE), TE = T0+K, T0 == t, K == 1.

time_ref(V, _, _) :- var(V), !, fail.
time_ref((X0:T0)+K, X, TE) :- T0 == t, integer(K), !, X = X0, TE = t+K.
time_ref((X0:T0)-K, X, TE) :- T0 == t, integer(K), !, X = X0, TE = t-K.
time_ref(X0:TE0, X, TE) :- !, X = X0, TE = TE0.
time_ref(current(X0), X, t) :- !, X = X0.
time_ref(prior(X0), X, 0) :- !, X = X0.
time_ref(T, X, TE) :- compound(T), arg(_, T, A), time_ref(A, X, TE).

classify_items([], _, _, [], []).
classify_items([t(T, L)|Ts], File, Id, Items, Dirs) :-
    (   var(T)
    ->  throw(error(ddc(unbound_head, File:L), _))
    ;   ( T = (:- D) ; T = (_ :- D) ), var(D)
    ->  throw(error(ddc(unbound_body, File:L), _))
    ;   sub_term(Z, T), compound(Z), compound_name_arity(Z, _, 0)
    ->  throw(error(ddc(zero_arity_compound(Z), File:L), _))
    ;   true
    ),
    (   T = (:- D)
    ->  Items = Items1, Dirs = [D-L|Dirs1], Id1 = Id
    ;   classify(T, Id, L, File, Item)
    ->  Items = [Item|Items1], Dirs = Dirs1, Id1 is Id+1
    ;   Items = [plain(T, L)|Items1], Dirs = Dirs1, Id1 = Id
    ),
    classify_items(Ts, File, Id1, Items1, Dirs1).

classify(T pr _, Id, L, File, Item) :- !,
    classify(T, Id, L, File, Item).
classify((H ~ D := B), Id, L, File, rv(Id, X, K, D1, B, L)) :- !,
    head_time(H, X, K, File, L), dist_sugar(D, D1).
classify((H ~ D <- B), Id, L, File, rv(Id, X, K, D1, B, L)) :- !,
    head_time(H, X, K, File, L), dist_sugar(D, D1).
classify((H ~ D), Id, L, File, rv(Id, X, K, D1, true, L)) :- !,
    head_time(H, X, K, File, L), dist_sugar(D, D1).
classify((H := B), Id, L, File, der(Id, X, K, B, L)) :- !,
    head_time(H, X, K, File, L),
    check_left_recursion(H, B, File:L).
classify((H <- B), Id, L, File, der(Id, X, K, B, L)) :- !,
    head_time(H, X, K, File, L),
    check_left_recursion(H, B, File:L).

%   check_left_recursion(+Head, +Body, +Where): a derived clause whose body
%   starts by proving its own head again (`p := p.`, `p(X) := p(X), q(X).`,
%   `h:t+1 := h:t+1.`) never terminates: the program's error at load, not
%   a stack overflow at run time.
check_left_recursion(H, B, Where) :-
    first_goal(B, G),
    nonvar(G), G == H, !,
    throw(error(ddc(left_recursion(H), Where), _)).
check_left_recursion(_, _, _).

first_goal(B, G) :- var(B), !, G = B.
first_goal((A, _), G) :- !, first_goal(A, G).
first_goal(B, B).

head_time(H, _, _, File, L) :-
    var(H), !,
    throw(error(ddc(unbound_head, File:L), _)).
head_time(X:(T+K), X, trans, _, _) :- T == t, K == 1, !.
head_time((X:T)+1, X, trans, _, _) :- T == t, !.
head_time(X:T, X, state, _, _) :- T == t, !.
head_time(X:N, X, fixed(N), _, _) :- integer(N), !.
head_time(current(X), X, state, _, _) :- nonvar(X), !.
head_time(next(X), X, trans, _, _) :- nonvar(X), !.
head_time(prior(X), X, fixed(0), _, _) :- nonvar(X), !.
head_time(H, _, _, File, L) :-
    \+ callable(H), !,
    throw(error(ddc(bad_head(H), File:L), _)).
head_time(H, H, u, _, _).

%   Distribution sugar (done at compile time).
dist_sugar(D, D) :- var(D), !.
dist_sugar(finite(L), finite(L)) :- is_list(L), !.
dist_sugar(finite(L), finite(L)) :- var(L), !.
dist_sugar(D, finite(L)) :-
    compound(D), compound_name_arguments(D, finite, Args), Args \= [], \+ (Args = [A], is_list(A)),
    forall(member(A, Args), nonvar(A)), forall(member(A, Args), A = _:_), !,
    L = Args.
dist_sugar(uniform(A, B), contUniform(A, B)) :- !.
dist_sugar(uniform(L), uniform(Lo:Hi)) :-   % a constant list Lo, Lo+1, ..., Hi: the
    integer_run(L, Lo, Hi), Hi > Lo, !.    % same draws, without walking the list
dist_sugar(D, D).

%   integer_run(+List, -First, -Last): List is First, First+1, ..., Last.
integer_run(L, Lo, Hi) :-
    is_list(L), L = [Lo|T], integer(Lo),
    integer_run_(T, Lo, Hi).

integer_run_([], Hi, Hi).
integer_run_([X|T], Prev, Hi) :-
    integer(X), X =:= Prev + 1,
    integer_run_(T, X, Hi).

%   Directives.
directives_options([], _, _, [], []).
directives_options([D-L|Ds], File, M, Opts, Cls) :-
    directive(D, File, L, M, Opts, Opts1, Cls, Cls1),
    directives_options(Ds, File, M, Opts1, Cls1).

directive(first_applicable(S), _, _, _, [first(S)|O], O, C, C) :- !.
directive(persistent(S), _, _, _, [persistent(S)|O], O, C, C) :- !.
directive(use_module(library(_)), _, _, _, O, O, C, C) :- !.   % libraries are visible anyway
directive(use_module(library(_), _), _, _, _, O, O, C, C) :- !.
directive(use_module(_), _, _, _, O, O, C, C) :- !.           % the original's own files
directive(use_module(_, _), _, _, _, O, O, C, C) :- !.
directive(ensure_loaded(_), _, _, _, O, O, C, C) :- !.
directive(initialization(_), _, _, _, O, O, C, C) :- !.        % the originals' test runners
directive(initialization(_, _), _, _, _, O, O, C, C) :- !.
directive(D, File, L, _, O0, O, C, C) :-
    original_directive(D, File:L, Os), !,      % set_options/1, ... (dc_compat_load.pl)
    append(Os, O, O0).
directive(dynamic(S), _, _, _, [facts(S)|O], O, C, C) :- !.   % read from a filter step's facts
directive(discontiguous(_), _, _, _, O, O, C, C) :- !.
directive(op(_, _, _), _, _, _, O, O, C, C) :- !.     % applied while reading (read_program/2)
directive(D, File, L, _, _, _, _, _) :-
    throw(error(ddc(bad_directive(D), File:L), _)).

%   persistent(Name/Arity): for each declared h, add after the program's
%   clauses  h:t+1 ~ val(V) := h:t ~= V  (random variable) or
%   h:t+1 := h:t (derived atom).
add_persistence(Opts, Items0, Items) :-
    findall(S, ( member(persistent(Spec), Opts), spec_list(Spec, Ss), member(S, Ss) ), Specs),
    (   Specs == []
    ->  Items = Items0
    ;   last_id(Items0, Id0),
        persistence_items(Specs, Items0, Id0, New),
        append(Items0, New, Items)
    ).

spec_list(Spec, L) :- is_list(Spec), !, L = Spec.
spec_list((A,B), L) :- !, spec_list(A, LA), spec_list(B, LB), append(LA, LB, L).
spec_list(S, [S]).

last_id(Items, Id) :-
    aggregate_all(max(I), ( member(It, Items), item_id(It, I) ), Max), !,
    ( Max == -inf -> Id = 0 ; Id = Max ).
last_id(_, 0).

item_id(rv(Id, _, _, _, _, _), Id).
item_id(der(Id, _, _, _, _), Id).

persistence_items([], _, _, []).
persistence_items([N/A|Ss], Items, Id0, New) :-
    functor(X, N, A),
    Id is Id0+1,
    (   member(rv(_, X0, _, _, _, L), Items), \+ X0 \= X
    ->  New = [rv(Id, X, persist, val(V), (X:t ~= V), L)|New1]
    ;   member(der(_, X0, _, _, L), Items), \+ X0 \= X
    ->  New = [der(Id, X, persist, X:t, L)|New1]
    ;   New = [rv(Id, X, persist, val(V), (X:t ~= V), 0)|New1]
    ),
    persistence_items(Ss, Items, Id, New1).

%   program_info(+Items, +Opts, -Info)
%   info(DerU, DerT, RvU, RvT, Plain, Impure, First)
program_info(Items, Opts, info(DerU, DerT, RvU, RvT, Plain, Impure, First)) :-
    findall(N/A, ( member(der(_, X, u, _, _), Items), functor(X, N, A) ), DU), sort(DU, DerU),
    findall(N/A, ( member(der(_, X, K, _, _), Items), K \== u, functor(X, N, A) ), DT), sort(DT, DerT),
    findall(N/A, ( member(rv(_, X, u, _, _, _), Items), functor(X, N, A) ), RU), sort(RU, RvU),
    findall(N/A, ( member(rv(_, X, K, _, _, _), Items), K \== u, functor(X, N, A) ), RT), sort(RT, RvT),
    findall(N/A, ( member(plain(C, _), Items), clause_head(C, H), functor(H, N, A) ), P0),
    findall(N/A, ( member(plain(builtin(P), _), Items), callable(P), functor(P, N, A) ), P1),
    append(P0, P1, P2), sort(P2, Plain),
    findall(S, ( member(first(Spec), Opts), spec_list(Spec, Ss), member(S, Ss) ), First),
    impure_preds(Items, Impure0),
    append(RvU, RvT, Rvs),
    clean_preds(Items, Rvs, Clean),
    findall(fact(S), ( member(facts(Spec), Opts), spec_list(Spec, Ss), member(S, Ss) ), Facts),
    append([Impure0, Clean, Facts], Impure).

clause_head((H :- _), H) :- !.
clause_head(H, H).

%   Derived predicates whose proof draws fresh randomness (true/1,
%   sample/2), directly or through other derived predicates: memoised.
impure_preds(Items, Impure) :-
    findall(K-Calls,
            ( member(der(_, X, Kind, B, _), Items),
              functor(X, N, A), tkind(Kind, TK), K = TK/N/A,
              body_calls(B, Calls) ),
            Edges),
    findall(K, ( member(K-Cs, Edges), memberchk(random, Cs) ), Seed0),
    sort(Seed0, Seed),
    callers_closure(Seed, Edges, Impure).

%   Derived predicates whose truth depends only on the facts asserted into
%   the world (and on plain Prolog, parameters, other such predicates):
%   no random variable is read, nothing random is drawn.  Listed in the
%   Impure slot of info/7 as clean(u/N/A) or clean(t/N/A).  All particles
%   of a filter step hold the same facts, so their answers are computed
%   once per step and shared ('$shared'/3).  Conservative: any doubt
%   (a variable goal, call/N, a random builtin, a term that names a random
%   variable) makes a predicate particle-dependent.
clean_preds(Items, Rvs, Clean) :-
    sort(Rvs, RvSet),
    pairs_keys_values(RvPairs, RvSet, RvSet),
    list_to_assoc(RvPairs, RvIndex),
    findall(K-Dirty-Calls,
            ( member(der(_, X, Kind, B, _), Items),
              functor(X, N, A), tkind(Kind, TK), K = TK/N/A,
              body_calls(B, Calls),
              ( body_dirty(B, RvIndex) -> Dirty = true ; Dirty = false ) ),
            Edges),
    findall(K, member(K-_-_, Edges), Ks0), sort(Ks0, Ks),
    findall(K, member(K-true-_, Edges), D0), sort(D0, Dirty0),
    findall(K-Calls, member(K-_-Calls, Edges), CallEdges),
    callers_closure(Dirty0, CallEdges, Dirty),
    ord_subtract(Ks, Dirty, CleanKs),
    findall(clean(K), member(K, CleanKs), Clean0),
    %   clean untimed predicates defined by unit clauses only (`object(o1)
    %   := true.`): a first-argument indexed lookup is cheaper than the
    %   shared table, so they are called directly (der_dispatch_u/5)
    findall(u/N/A, ( member(der(_, X, Kind, B, _), Items), tkind(Kind, u), B \== true,
                     functor(X, N, A) ), NonUnit0),
    sort(NonUnit0, NonUnit),
    ord_subtract(CleanKs, NonUnit, UnitKs),
    findall(unit(K), ( member(K, UnitKs), K = u/_/_ ), Units),
    append(Clean0, Units, Clean).

%   callers_closure(+Seeds, +Edges, -Closure): Closure (an ordered set) is
%   Seeds and every key K of Edges (K-Calls pairs, a key may have several)
%   that calls, directly or through other keys, a key of Seeds.  A search
%   from the seeds over the reversed calls, each key visited once.
callers_closure(Seeds, Edges, Closure) :-
    findall(C-K, ( member(K-Cs, Edges), member(C, Cs) ), Rev0),
    sort(Rev0, Rev),
    group_pairs_by_key(Rev, Callers),
    list_to_assoc(Callers, CallersOf),
    pairs_keys_values(SeedPairs, Seeds, Seeds),
    list_to_assoc(SeedPairs, Seen0),
    callers_visit(Seeds, CallersOf, Seen0, Seen),
    assoc_to_keys(Seen, Closure).

callers_visit([], _, Seen, Seen).
callers_visit([K|Ks], CallersOf, Seen0, Seen) :-
    (   get_assoc(K, CallersOf, Cs) -> true ; Cs = [] ),
    foldl(callers_new, Cs, Seen0-Ks, Seen1-Ks1),
    callers_visit(Ks1, CallersOf, Seen1, Seen).

callers_new(C, Seen0-Ks, Seen-Ks1) :-
    (   get_assoc(C, Seen0, _)
    ->  Seen = Seen0, Ks1 = Ks
    ;   put_assoc(C, Seen0, C, Seen), Ks1 = [C|Ks]
    ).

body_dirty(B, _) :- body_call(B, '$var'), !.
body_dirty(B, _) :- body_call(B, u/N/_), ( N == call ; sub_atom(N, _, _, _, random) ), !.
body_dirty(B, RvIndex) :-
    sub_term(S, B), nonvar(S),
    (   S = (_ ~= _)
    ;   S = true(_)
    ;   S = sample(_, _)
    ;   S = X:_, nonvar(X), callable(X), functor(X, N, A), get_assoc(N/A, RvIndex, _)
    ;   callable(S), functor(S, N, A), get_assoc(N/A, RvIndex, _)
    ), !.

tkind(u, u) :- !.
tkind(_, t).

body_calls(B, Calls) :-
    findall(C, body_call(B, C), Calls).

body_call(V, '$var') :- var(V), !.
body_call((A,B), C) :- !, ( body_call(A, C) ; body_call(B, C) ).
body_call((A;B), C) :- !, ( body_call(A, C) ; body_call(B, C) ).
body_call((A->B), C) :- !, ( body_call(A, C) ; body_call(B, C) ).
body_call((A*->B), C) :- !, ( body_call(A, C) ; body_call(B, C) ).
body_call(\+ A, C) :- !, body_call(A, C).
body_call(findall(_, G, _), C) :- !, body_call(G, C).
body_call(findall_forward(_, G, _), C) :- !, body_call(G, C).
body_call(forall(A, B), C) :- !, ( body_call(A, C) ; body_call(B, C) ).
body_call(once(A), C) :- !, body_call(A, C).
body_call(true(_), random) :- !.
body_call(sample(_, _), random) :- !.
body_call(_ ~= _, _) :- !, fail.
body_call(X:_, t/N/A) :- callable(X), !, functor(X, N, A).
body_call((X:_)+_, t/N/A) :- callable(X), !, functor(X, N, A).
body_call(G, u/N/A) :- callable(G), functor(G, N, A).

clause_positions(Items, File, Ps) :-
    findall('$rv_pos'(Id, File, L),
            ( member(I, Items), item_id(I, Id), item_line(I, L) ), Ps).

item_line(rv(_, _, _, _, _, L), L).
item_line(der(_, _, _, _, L), L).

%   compile_item_at(+Item, +File, +Info, +RivalsOf, -Clause) is nondet.
%
%   compile_item/5, with any error of compiling or checking the item (an
%   atom where arithmetic needs a function, a plain clause for a control
%   construct or a built-in predicate, `observed()`) the program's error at
%   the item's line.
compile_item_at(I, File, Info, RivalsOf, '$at'(Line, C)) :-
    item_where(I, File, Where),
    Where = _:Line,
    b_setval(ddc_compiling, Where),
    catch(compile_item(I, File, Info, RivalsOf, C), E, item_error(E, I, File)),
    check_clause(C, I, Where).

item_error(E, I, File) :-
    item_where(I, File, Where),
    load_error(E, I, Where).

item_where(plain(_, L), File, File:L) :- !.
item_where(I, File, File:L) :- item_line(I, L), !.
item_where(_, File, File:0).

%   load_error(+Error, +Culprit, +Where): rethrow Error of loading
%   Culprit as the program's error at Where (an engine error that already
%   names a line keeps it).
load_error(error(ddc(C, W0), _), _, Where) :- !,
    (   W0 = _:L0, integer(L0), L0 > 0 -> W = W0 ; W = Where ),
    throw(error(ddc(C, W), _)).
load_error(E, _, Where) :-
    throw(error(ddc(prolog_error(E), Where), _)).

%   check_clause(+Clause, +Item, +Where): the errors assertz/1 would raise
%   when the program is installed, found before anything is replaced: a
%   head that is a control construct or a system predicate, and arithmetic
%   (compiled inline) on an atom that is not an arithmetic function.
check_clause(C, I, Where) :-
    (   C = (H :- B) -> true ; H = C, B = true ),
    (   var(H)
    ->  true
    ;   ( \+ callable(H) ; timed_plain_head(H) )
    ->  throw(error(ddc(bad_head(H), Where), _))
    ;   predicate_property(system:H, iso)
    ->  functor(H, N, A),
        load_error(error(permission_error(modify, static_procedure, N/A), _), I, Where)
    ;   arithmetic_atom(B, Atom)
    ->  load_error(error(type_error(evaluable, Atom/0), _), I, Where)
    ;   term_variables(H, Seen),
        \+ fresh_arithmetic(B, Seen, _)
    ->  throw(error(ddc(fresh_arithmetic, Where), _))
    ;   true
    ).

%   fresh_arithmetic(+Body, +Seen0, -Seen) fails when an arithmetic goal
%   that the compiler inlines (is/2 or a comparison, in a conjunction,
%   disjunction, if-then-else or negation) reads a variable that occurs
%   nowhere before it in the clause: assertz/1 would refuse the clause.
fresh_arithmetic(G, Seen0, Seen) :-
    var(G), !, Seen = [G|Seen0].
fresh_arithmetic(G, Seen0, Seen) :-
    compound(G), compound_name_arity(G, Op, 2),
    memberchk(Op, [',', ;, ->, *->]), !,
    arg(1, G, A), arg(2, G, B),
    fresh_arithmetic(A, Seen0, Seen1),
    fresh_arithmetic(B, Seen1, Seen).
fresh_arithmetic(\+ G, Seen0, Seen) :- !,
    fresh_arithmetic(G, Seen0, Seen).
fresh_arithmetic(G, Seen0, Seen) :-
    compound(G), compound_name_arity(G, Op, 2),
    memberchk(Op, [is, <, >, =<, >=, =:=, =\=]), !,
    arg(2, G, R), arg(1, G, L),
    (   Op == is -> Read = R ; Read = L-R ),
    term_variables(Read, Vs),
    forall(member(V, Vs), memberchk_eq(V, Seen0)),
    term_variables(L, Ls),
    append(Ls, Seen0, Seen).
fresh_arithmetic(G, Seen0, Seen) :-
    term_variables(G, Vs),
    append(Vs, Seen0, Seen).

%   A plain clause whose head is a time-indexed term (`observed(a):t+1.`, a
%   line of data rather than of a program) is not a clause of the program.
timed_plain_head(H) :-
    (   H = _:_ -> true ; H = (X:_)+_, nonvar(X) -> true ; H = (X:_)-_, nonvar(X) ).

%   arithmetic_atom(+Body, -Atom): Atom appears where Body's arithmetic
%   (is/2 and the comparisons) needs a number and is not a function.
arithmetic_atom(B, Atom) :-
    sub_term(G, B), compound(G),
    compound_name_arity(G, Op, 2),
    memberchk(Op, [is, <, >, =<, >=, =:=, =\=]),
    arg(Side, G, Expr), ( Op == is -> Side == 2 ; true ),
    sub_term(Atom, Expr), atom(Atom), Atom \== [],
    \+ current_arithmetic_function(Atom), !.

%   compile_item(+Item, +File, +Info, +RivalsOf, -Clause) is nondet.
%   RivalsOf: rivals_table/3 of the program's items.
compile_item(plain(builtin(_), _), _, _, _, _) :- !, fail.
compile_item(plain(C, _), _, _, _, C).
compile_item(rv(Id, X, K, D, B, L), File, Info, RivalsOf, Clause) :-
    compile_rv(Id, X, K, D, B, L, File, Info, RivalsOf, Clause).
compile_item(der(Id, X, K, B, _), _, Info, _, Clause) :-
    compile_der(Id, X, K, B, Info, Clause).

%   '$rv'(X, T, W, Skip, Ev, Out, Tier, Id, Rivals)
compile_rv(Id, X, K, D0, B0, L, File, Info, RivalsOf, Clause) :-
    Head = '$rv'(X, TArg, W, Skip, Ev, Out, Tier, Id, Rivals),
    tier(K, Tier),
    rivals(Id, RivalsOf, Rivals),
    time_guard(K, TArg, W, Tc, Guard),
    Ctx = ctx(W, Tc, Info, clause),
    range_support(X, D0, B0, D, B),
    catch(cb(B, Ctx, BodyCode), E, clause_compile_error(E, File, L)),
    (   ground(X) -> GroundCheck = true
    ;   GroundCheck = ( ground(X) -> true ; ddc:'$clause_error'(W, Id, non_ground_head(X)) )
    ),
    dist_code(D, Id, File, L, Out0, DistCode),
    (   D = val(V), var(V),
        invert_val_body(B, V, Ctx, EvVal, LJ, InvCode)
    ->  Body = ( Id > Skip, Guard,
                 (   Ev == none
                 ->  BodyCode, GroundCheck, DistCode, Out = Out0
                 ;   Ev = ev(EvVal), InvCode, GroundCheck, Out = '$prop'(LJ)
                 ) )
    ;   Body = ( Id > Skip, Guard, BodyCode, GroundCheck, DistCode, Out = Out0 )
    ),
    drop_unused_time(Guard, Tc, Body, Body1),
    Clause = (Head :- Body1).

%   range_support(+Head, +Dist, +Body, -Dist1, -Body1): a clause that builds
%   the list of integers Lo..Hi only to be the support of a uniform
%   (`x ~ uniform(L) := ..., findall(I, between(Lo, Hi, I), L).`) draws
%   from the range itself, uniform(Lo:Hi): the same value for the same random
%   state, and the mass of a value without building or scanning the list.
%   Only when L is used nowhere else.  (An empty range is the same error,
%   empty_support, shown as uniform(Lo:Hi) instead of uniform([]).)
range_support(X, uniform(L), B, uniform(Lo1:Hi1), B1) :-
    var(L), \+ occurs_in(L, X),
    conj_list(B, Ls),
    select(F, Ls, ddc:'$range_bounds'(Lo, Hi, Lo1, Hi1), Ls1),
    nonvar(F), F = findall(T, G, L2), L2 == L, var(T),
    nonvar(G), G = between(Lo, Hi, T1), T1 == T, \+ occurs_in(T, Lo-Hi),
    term_variables(Ls1, Vs), \+ memberchk_eq(L, Vs),
    !,
    conj_from_list(Ls1, B1).
range_support(_, D, B, D, B).

%   '$range_bounds'(+Lo, +Hi, -Lo1, -Hi1): the integer bounds of a range,
%   with between/3's errors.
'$range_bounds'(Lo, Hi, Lo1, Hi1) :-
    Lo1 is Lo, Hi1 is Hi,
    must_be(integer, Lo1),
    must_be(integer, Hi1).

%   An untimed clause reads the world's time only if its body uses it.
drop_unused_time(Guard, Tc, Body, Body1) :-
    (   Guard = arg(3, _, Tc0), Tc0 == Tc,
        Body = (A, G, Rest), G == Guard,
        \+ occurs_in(Tc, Rest)
    ->  Body1 = (A, Rest)
    ;   Body1 = Body
    ).

%   '$sweep_key'(Id, X, T, W): the candidate heads X of transition clause
%   Id at time T: the shortest prefix of its body that binds the head's
%   variables (the filter's sweep then reads each candidate, which picks
%   the clause that applies; running whole bodies there would be wasted).
%   distinct_sweep_keys(+Id-Kind-Clause, -Kept): the clauses of one random
%   variable often share the prefix that enumerates their heads
%   (`object(O)`): the sweep reads each key once, so a clause whose key
%   enumerator is a variant of an earlier one (same kind) is left out.
%   The keys kept so far are found by the variant hash of their kind and
%   shape (variant terms have the same hash), each candidate then compared
%   with =@=: linear in the number of clauses.
distinct_sweep_keys(SwKs, Kept) :-
    empty_assoc(Seen),
    distinct_sweep_keys(SwKs, Seen, Kept).

distinct_sweep_keys([], _, []).
distinct_sweep_keys([Id-K-C|T], Seen0, Kept) :-
    sweep_key_shape(C, S),
    variant_sha1(K-S, Hash),
    (   get_assoc(Hash, Seen0, Shapes) -> true ; Shapes = [] ),
    (   member(K0-S0, Shapes), K0-S0 =@= K-S
    ->  Kept = Kept1, Seen = Seen0
    ;   Kept = [Id-K-C|Kept1],
        put_assoc(Hash, Seen0, [K-S|Shapes], Seen)
    ),
    distinct_sweep_keys(T, Seen, Kept1).

sweep_key_shape(('$sweep_key'(_, X, T, W) :- B), s(X, T, W, B)).

sweep_key_clause(Id, X, K, B, Info, ('$sweep_key'(Id, X, TArg, W) :- Guard, Code)) :-
    time_guard(K, TArg, W, Tc, Guard),
    sweep_prefix(X, B, PB),
    cb(PB, ctx(W, Tc, Info, clause), Code).

sweep_prefix(X, B, PB) :-
    conj_list(B, Ls),
    term_variables(X, HVs),
    binding_prefix(Ls, HVs, Prefix),
    conj_from_list(Prefix, PB).

binding_prefix(_, [], []) :- !.
binding_prefix([], _, []).
binding_prefix([L|Ls], Vs, [L|P]) :-
    (   binds_nothing(L) -> Vs1 = Vs
    ;   term_variables(L, LVs), vars_not_in(Vs, LVs, Vs1)
    ),
    binding_prefix(Ls, Vs1, P).

binds_nothing(L) :- var(L), !, fail.
binds_nothing(\+ _).
binds_nothing(L) :- compound(L), functor(L, Op, 2), memberchk(Op, [<, >, =<, >=, =:=, =\=, \==, ==]).

vars_not_in([], _, []).
vars_not_in([V|Vs], LVs, Out) :-
    (   memberchk_eq(V, LVs) -> Out = Out1 ; Out = [V|Out1] ),
    vars_not_in(Vs, LVs, Out1).

memberchk_eq(X, L) :- nonvar(L), L = [Y|Ys], ( X == Y -> true ; memberchk_eq(X, Ys) ).

clause_compile_error(error(ddc(C, _), _), File, L) :- !,
    throw(error(ddc(C, File:L), _)).
clause_compile_error(E, _, _) :- throw(E).

tier(state, 2) :- !.
tier(_, 1).

time_guard(u, u, W, Tc, arg(3, W, Tc)).
time_guard(state, Tc, _, Tc, integer(Tc)).
time_guard(trans, T, W, Tc, (integer(T), T >= 1, ddc:'$live'(W, T), Tc is T-1)).
time_guard(persist, T, W, Tc, (integer(T), T >= 1, ddc:'$live'(W, T), Tc is T-1)).
time_guard(fixed(N), N, W, N, ddc:'$live'(W, N)).

%   rivals(+Id, +RivalsOf, -R): R is true if a later clause of the same
%   tier than random variable clause Id can define a variable that Id can
%   also define (their heads unify, their kinds of time overlap: the same
%   kind, or h:t+1 and h:N with N >= 1), false if none can or if Id's
%   variable is persistent or first_applicable.  RivalsOf is
%   rivals_table/3's.
rivals(Id, RivalsOf, R) :-
    get_assoc(Id, RivalsOf, R).

%   rivals_table(+Items, +Info, -RivalsOf): the assoc from the Id of each
%   random variable clause of Items to rivals/3's R.  The clauses are
%   visited from the last to the first: each one asks whether a head
%   entered so far unifies with its own, then enters its head, so that
%   only later clauses are asked.  The heads are facts of a temporary
%   module, one predicate per kind of time and name (rival_entry/3), and
%   asking is calling them: SWI-Prolog's clause indexing (on any argument,
%   also inside compound ones) answers without looking at every later
%   clause, which keeps loading near-linear in the number of clauses.
rivals_table(Items, info(_, _, _, _, _, _, First), RivalsOf) :-
    findall(r(Id, X, K), member(rv(Id, X, K, _, _, _), Items), Rvs0),
    sort(1, @>=, Rvs0, Rvs),
    in_temporary_module(Later, true, foldl(ddc:rival(First, Later), Rvs, [], Pairs)),
    list_to_assoc(Pairs, RivalsOf).

rival(First, Later, r(Id, X, K), Pairs, [Id-R|Pairs]) :-
    functor(X, N, A),
    (   ( K == persist ; memberchk(all, First) ; memberchk(N/A, First) )
    ->  R = false
    ;   rival_questions(K, Qs),
        member(QTable-QExtra, Qs),
        rival_fact(Later, QTable, QExtra, X, G),
        current_predicate(_, G),
        \+ \+ call(G)
    ->  R = true
    ;   R = false
    ),
    (   K == persist
    ->  true
    ;   rival_entry(K, Table, Extra),
        rival_fact(Later, Table, Extra, X, F),
        assertz(F)
    ).

%   rival_entry(+Kind, -Table, -Extra): the table a head of Kind is entered
%   in, with Extra before the head's arguments.
rival_entry(u, u, []).
rival_entry(state, state, []).
rival_entry(trans, trans, []).
rival_entry(fixed(N), Table, [N]) :-
    (   N >= 1 -> Table = later ; Table = early ).

%   rival_questions(+Kind, -Tables): the tables holding the heads that a
%   clause of Kind overlaps with (h:t+1 overlaps h:N for N >= 1).
rival_questions(u, [u-[]]).
rival_questions(state, [state-[]]).
rival_questions(trans, [trans-[], later-[_]]).
rival_questions(fixed(N), Qs) :-
    (   N >= 1 -> Qs = [trans-[], later-[N]] ; Qs = [early-[N]] ).

rival_fact(Later, Table, Extra, X, Later:F) :-
    X =.. [N|Args],
    atomic_list_concat(['$rival', Table, N], '|', Name),
    append(Extra, Args, FArgs),
    F =.. [Name|FArgs].

%   Distribution code: evaluate arithmetic in the parameters; check at
%   load time when the parameters are ground, at run time otherwise.
dist_code(D, Id, File, L, Out, Code) :-
    (   var(D)
    ->  Out = '$chk'(D, Id), Code = true
    ;   ground(D)
    ->  catch(eval_dist(D, D1), E, dist_eval_error(E, D, File, L)),
        catch(dist_check(D1), error(ddc_distribution(DE, Why), _),
              throw(error(ddc(distribution(DE, Why), File:L), _))),
        Out = D1, Code = true
    ;   needs_eval(D)
    ->  Code = ddc:eval_dist(D, D1), Out = '$chk'(D1, Id)
    ;   Out = '$chk'(D, Id), Code = true
    ).

dist_eval_error(E, D, File, L) :-
    message_to_codes_safe(E, Why),
    throw(error(ddc(distribution(D, Why), File:L), _)).

message_to_codes_safe(E, S) :-
    catch(message_to_codes(E, S0), _, fail), !, S = S0.
message_to_codes_safe(E, E).

message_to_codes(E, S) :-
    '$messages':translate_message(E, Lines, []),
    with_output_to(string(S), print_message_lines(current_output, '', Lines)).

needs_eval(D) :-
    compound(D),
    compound_name_arguments(D, N, Args),
    (   memberchk(N, [finite, propfinite, logfinite])
    ->  Args = [L], nonvar(L), is_list(L),
        member(P:_, L), compound(P)
    ;   memberchk(N, [val, uniform])
    ->  N == uniform, Args = [A:C], ( compound(A) ; compound(C) )
    ;   member(A, Args), param_needs_eval(A)
    ), !.

param_needs_eval(A) :- var(A), !, fail.
param_needs_eval([H|T]) :- !, ( param_needs_eval(H) ; param_needs_eval(T) ).
param_needs_eval((A,B)) :- !, ( param_needs_eval(A) ; param_needs_eval(B) ).
param_needs_eval(A) :- compound(A).

%!  eval_dist(+D0, -D) is det.
%
%   Evaluates arithmetic expressions in the numeric parameters of D0.
eval_dist(D0, D) :-
    compound(D0), !,
    compound_name_arguments(D0, N, Args0),
    (   memberchk(N, [finite, propfinite, logfinite]), Args0 = [L0], is_list(L0)
    ->  maplist(eval_pair, L0, L), Args = [L]
    ;   N == val
    ->  Args = Args0
    ;   N == uniform, Args0 = [S0]
    ->  (   nonvar(S0), S0 = A0:C0 -> eval_param(A0, A), eval_param(C0, C), Args = [A:C]
        ;   Args = Args0 )
    ;   maplist(eval_param, Args0, Args)
    ),
    compound_name_arguments(D, N, Args).
eval_dist(D, D).

eval_pair(P0:V, P:V) :- !, eval_num(P0, P).
eval_pair(X, X).

eval_param(X, X) :- var(X), !.
eval_param(X, X) :- number(X), !.
eval_param([], []) :- !.
eval_param([H0|T0], [H|T]) :- !, eval_param(H0, H), eval_param(T0, T).
eval_param((A0,B0), (A,B)) :- !, eval_param(A0, A), eval_param(B0, B).
eval_param(X, X) :- atom(X), \+ catch(_ is X, _, fail), !.
eval_param(X, Y) :- eval_num(X, Y).

eval_num(X, X) :- number(X), !.
eval_num(X, Y) :- Y is X.

%   Evidence on h ~ val(V) := ..., r ~= A, V is f(A).  The inverted body
%   reads r with the evidence value f^-1(v) and binds LJ to log |d f^-1/dv|.
invert_val_body(B, V, Ctx, EvVal, LJ, InvCode) :-
    conj_list(B, Ls),
    (   append(Pre, [Is], Ls), nonvar(Is), Is = (V1 is E), V1 == V,
        term_variables(E, [A]),
        select_read(Pre, A, Before, R, After),
        \+ occurs_in(V, Before-After),
        inv(E, A, EvVal, InvGoal, Scale)
    ->  LJGoal = (LJ is -log(abs(Scale)))
    ;   select_read(Ls, V, Before, R, After),
        A = V, InvGoal = (A = EvVal), LJGoal = (LJ = 0.0)
    ),
    Ctx = ctx(W, _, _, _),
    conj_from_list(Before, BB), conj_from_list(After, BA),
    cb(BB, Ctx, CB), cb(BA, Ctx, CA),
    read_key_code(R, Ctx, X, T, TG),
    InvCode = ( CB, InvGoal, TG, ddc:'$read_ev'(X, T, A, W), CA, LJGoal ).

occurs_in(V, T) :- term_variables(T, Vs), member(X, Vs), X == V, !.

select_read(Ls, A, Before, R, After) :-
    append(Before, [(R ~= A1)|After], Ls), A1 == A, !.

%   inv(+E, +A, +V, -Goal, -Scale): A is the unique variable of E; Goal
%   computes A from V with V = E; Scale = dV/dA (the Jacobian's factor).
inv(E, A, V, (A = V), 1) :- E == A, !.
inv(E1*C, A, V, G, S) :- \+ occurs_in(A, C), !, inv(E1, A, V1, G1, S1), G = (V1 is V/C, G1), S = S1*C.
inv(C*E1, A, V, G, S) :- \+ occurs_in(A, C), !, inv(E1, A, V1, G1, S1), G = (V1 is V/C, G1), S = S1*C.
inv(E1/C, A, V, G, S) :- \+ occurs_in(A, C), !, inv(E1, A, V1, G1, S1), G = (V1 is V*C, G1), S = S1/C.
inv(E1+C, A, V, G, S) :- \+ occurs_in(A, C), !, inv(E1, A, V1, G1, S), G = (V1 is V-C, G1).
inv(C+E1, A, V, G, S) :- \+ occurs_in(A, C), !, inv(E1, A, V1, G1, S), G = (V1 is V-C, G1).
inv(E1-C, A, V, G, S) :- \+ occurs_in(A, C), !, inv(E1, A, V1, G1, S), G = (V1 is V+C, G1).
inv(C-E1, A, V, G, S) :- \+ occurs_in(A, C), !, inv(E1, A, V1, G1, S), G = (V1 is C-V, G1).
inv(-E1, A, V, G, S) :- !, inv(E1, A, V1, G1, S), G = (V1 is -V, G1).

conj_list(V, [V]) :- var(V), !.
conj_list((A,B), L) :- !, conj_list(A, LA), conj_list(B, LB), append(LA, LB, L).
conj_list(true, []) :- !.
conj_list(G, [G]).

conj_from_list([], true).
conj_from_list([G], G) :- !.
conj_from_list([G|Gs], (G, C)) :- conj_from_list(Gs, C).

%   Derived atoms.
compile_der(Id, X, K, B, Info, Clause) :-
    Info = info(_, _, _, _, _, Impure, _),
    X =.. [N|Args],
    Ctx = ctx(W, Tc, Info, clause),
    cb(B, Ctx, BodyCode0),
    %   a derived atom is a ground fact of the world: a head left with
    %   variables by its body (`covers(O, A) := category(O, hand), A \== O`)
    %   is the clause's error, not an atom dropped or stored unbound
    (   ground(X)
    ->  BodyCode = BodyCode0
    ;   BodyCode = ( BodyCode0,
                     ( ground(X) -> true ; ddc:'$clause_error'(W, Id, non_ground_head(X)) ) )
    ),
    length(Args, Ar),
    (   K == u
    ->  (   memberchk(u/N/Ar, Impure) -> Kind = d0
        ;   memberchk(clean(u/N/Ar), Impure) -> Kind = ds
        ;   Kind = d
        ),
        derived_name(N, Kind, DN),
        append(Args, [W], HArgs),
        Head =.. [DN|HArgs],
        (   occurs_in(Tc, BodyCode)
        ->  Clause = (Head :- arg(3, W, Tc), BodyCode)
        ;   Clause = (Head :- BodyCode)
        )
    ;   tier(K, Tier),
        ( Tier == 2 -> Kind = dt2 ; Kind = dt1 ),
        derived_name(N, Kind, DN),
        time_guard(K, TArg, W, Tc, Guard),
        append(Args, [TArg, W], HArgs),
        Head =.. [DN|HArgs],
        Clause = (Head :- Guard, BodyCode)
    ).

%   One dispatcher per derived predicate: world facts first, then the
%   program's clauses (memoised when impure); timed ones read materialised
%   facts at frozen times.
derived_dispatchers(M, Info, Cs) :-
    Info = info(DerU, DerT, _, _, _, Impure, _),
    findall(C, ( member(N/A, DerU), der_dispatch_u(M, N, A, Impure, C) ), Cu),
    findall(C, ( member(N/A, DerT), der_dispatch_t(M, N, A, Impure, C) ), Ct),
    append(Cu, Ct, Cs).

der_dispatch_u(M, N, A, Impure, C) :-
    length(Args, A),
    G =.. [N|Args],
    derived_name(N, d, DN),
    append(Args, [W], HArgs),
    Head =.. [DN|HArgs],
    (   memberchk(clean(u/N/A), Impure)
    ->  derived_name(N, ds, DNS),
        HS =.. [DNS|HArgs],
        (   (   memberchk(unit(u/N/A), Impure)
            ->  C = (Head :- HS)
            ;   C = (Head :- ddc:'$shared'(G, G, M:HS))
            )
        ;   C = (HS :- ddc:'$fact'(W, G))
        )
    ;   C = (Head :- ddc:'$fact'(W, G))
    ;   memberchk(u/N/A, Impure),
        derived_name(N, d0, DN0),
        Call =.. [DN0|HArgs],
        C = (Head :- ( ground(G) -> ddc:'$memo'(W, G, Call) ; Call ))
    ).

der_dispatch_t(M, N, A, Impure, C) :-
    length(Args, A),
    G =.. [N|Args],
    append(Args, [T, W], HArgs),
    derived_name(N, dt, DN), Head =.. [DN|HArgs],
    derived_name(N, dt0, DN0), H0 =.. [DN0|HArgs],
    derived_name(N, dt1, DN1), H1 =.. [DN1|HArgs],
    derived_name(N, dt2, DN2), H2 =.. [DN2|HArgs],
    (   memberchk(t/N/A, Impure)
    ->  (   %   (at a frozen time the materialised atoms are read directly: a
            %   memo of that read would only add its own bookkeeping)
            C = (Head :- (   ddc:'$frozen_at'(W, T)
                         ->  ( ground(G) -> once(H0) ; H0 )
                         ;   ground(G)
                         ->  ddc:'$memo'(W, G:T, H0)
                         ;   H0
                         ))
        ;   C = (H0 :- ( ddc:'$frozen_at'(W, T) -> ddc:'$mat'(W, G, T) ; H1 ))
        ;   C = (H0 :- H2)
        ;   C = (H0 :- ddc:'$fact'(W, G:T))
        )
    ;   memberchk(clean(t/N/A), Impure)
    ->  derived_name(N, dts, DNS), HS =.. [DNS|HArgs],
        (   C = (Head :- ddc:'$shared'(G:T, G:T, M:HS))
        ;   C = (HS :- ( ddc:'$frozen_at'(W, T) -> ddc:'$mat'(W, G, T) ; H1 ))
        ;   C = (HS :- H2)
        ;   C = (HS :- ddc:'$fact'(W, G:T))
        )
    ;   (   C = (Head :- ( ddc:'$frozen_at'(W, T) -> ddc:'$mat'(W, G, T) ; H1 ))
        ;   C = (Head :- H2)
        ;   C = (Head :- ddc:'$fact'(W, G:T))
        )
    ).

                 /*******************************
                 *        BODY COMPILATION      *
                 *******************************/

%   cb(+Goal, +Ctx, -Code): Ctx = ctx(W, Tc, Info, Kind), Kind clause or
%   query (in a query, an untimed read of a variable only defined with a
%   time index means its value at the current time).

cb(G, _, call(G)) :- var(G), !.
cb(true, _, true) :- !.
cb((A,B), C, (CA,CB)) :- !, cb(A, C, CA), cb(B, C, CB).
cb((A;B), C, (CA;CB)) :- !, cb(A, C, CA), cb(B, C, CB).
cb((A->B), C, (CA->CB)) :- !, cb(A, C, CA), cb(B, C, CB).
cb((A*->B), C, (CA*->CB)) :- !, cb(A, C, CA), cb(B, C, CB).
cb(\+ A, C, \+ CA) :- !, cb(A, C, CA).
cb(once(A), C, once(CA)) :- !, cb(A, C, CA).
cb(ignore(A), C, ignore(CA)) :- !, cb(A, C, CA).
cb(forall(A,B), C, forall(CA,CB)) :- !, cb(A, C, CA), cb(B, C, CB).
cb(findall(T,G,L), _, Code) :-              % peephole: a range of integers
    var(T), nonvar(G), G = between(Lo, Hi, T1), T1 == T,
    \+ occurs_in(T, Lo-Hi), !,
    Code = ( Lo1 is Lo, Hi1 is Hi,
             ( integer(Lo1), integer(Hi1) -> ddc:range_(Lo1, Hi1, L) ; ddc:'$range'(Lo1, Hi1, L) ) ).
cb(findall(T,G,L), C, findall(T,CG,L)) :- !, cb(G, C, CG).
cb(findall(T,G,L,R), C, findall(T,CG,L,R)) :- !, cb(G, C, CG).
cb(findall_forward(T,G,L), C, findall(T,CG,L)) :- !, cb(G, C, CG).
cb(aggregate_all(S,G,R), C, aggregate_all(S,CG,R)) :- !, cb(G, C, CG).
cb(H ~= V, C, Code) :- !,
    read_key_code(H, C, X, T, TG),
    Ctx = C, Ctx = ctx(W, _, _, _),
    (   ground(X)
    ->  Code = (TG, ddc:read_key(X, T, V, W))
    ;   Code = (TG, ddc:'$read'(X, T, V, W))
    ).
cb(true(P), _, ddc:'$flip'(P)) :- !.
cb(sample(D, X), _, ddc:'$sample_inline'(D, X)) :- !.
cb(belief(A), _, ground(A)) :- !.
cb(timestep(T), ctx(_, Tc, _, _), (T = Tc)) :- !.
cb(G, _, ddc_models:G) :-                   % logistic/3, linear/3, softmax/3, mean_list/2, ...
    callable(G), predicate_property(ddc_models:G, exported), !.
cb(G, C, Code) :-
    compound(G), functor(G, Op, 2), memberchk(Op, [<, >, =<, >=, =:=, =\=]),
    G =.. [Op, A, B],
    ( rv_operand(A) ; rv_operand(B) ), !,
    operand_code(A, C, A1, CA),
    operand_code(B, C, B1, CB),
    G1 =.. [Op, A1, B1],
    Code = (CA, CB, G1).
cb(G, C, Code) :-
    timed_atom(G, X, TE), !,
    C = ctx(W, Tc, Info, Kind),
    time_code(TE, Tc, T, TG),
    timed_call(X, T, W, Info, Call0),
    (   Kind \== query, Call0 = ddc:'$undefined'(W, XT)
    ->  functor(X, N, A), note_undefined(N/A, Info),
        Call = ddc:'$fact'(W, XT)
    ;   Call = Call0
    ),
    Code = (TG, Call).
cb(G, C, Code) :-
    callable(G), !,
    C = ctx(W, Tc, Info, Kind),
    functor(G, N, A),
    Info = info(DerU, DerT, _, _, Plain, _, _),
    (   memberchk(N/A, DerU)
    ->  G =.. [N|Args], derived_name(N, d, DN), append(Args, [W], CArgs), Code =.. [DN|CArgs]
    ;   Kind == query, memberchk(N/A, DerT)
    ->  timed_call(G, Tc, W, Info, Code)
    ;   memberchk(N/A, Plain)
    ->  Code = G
    ;   prolog_callable(G)
    ->  Code = G
    ;   Kind == query
    ->  Code = ddc:'$undefined'(W, G)
    ;   note_undefined(N/A, Info),
        Code = ddc:'$fact'(W, G)
    ).

cb(G, _, _) :-
    type_error(callable, G).

%   note_undefined(+PI, +Info): a body calls PI, which the program defines
%   nowhere and does not declare (`:- dynamic(PI).`, the predicates a
%   filter step's facts define): remembered with the line of the clause
%   being compiled, for the warning of warn_undefined/1.
:- thread_local undefined_call_/2.

note_undefined(PI, info(_, _, _, _, _, Impure, _)) :-
    (   memberchk(fact(PI), Impure) -> true
    ;   undefined_call_(PI, _) -> true
    ;   nb_current(ddc_compiling, Where), Where \== []
    ->  assertz(undefined_call_(PI, Where))
    ;   true
    ).

%   warn_undefined: one warning per predicate called in the program's
%   bodies and defined nowhere: it holds only for the facts of a filter
%   step, and is false in a static query.
warn_undefined :-
    forall(retract(undefined_call_(PI, Where)),
           print_message(warning, error(ddc(undefined_predicate(PI), Where), _))).


rv_operand(X) :- nonvar(X), X = _:_, \+ number(X).
rv_operand(X) :- nonvar(X), X = (Y:_)+_, nonvar(Y).

operand_code(A, C, V, Code) :-
    rv_operand(A), !,
    cb(A ~= V, C, Code).
operand_code(A, _, A, true).

timed_atom(G, X, TE) :- compound(G), G = (X0:T0)+K, T0 == t, integer(K), callable(X0), !, X = X0, TE = t+K.
timed_atom(G, X, TE) :- compound(G), G = (X0:T0)-K, T0 == t, integer(K), callable(X0), !, X = X0, TE = t-K.
timed_atom(G, X, TE) :- compound(G), G = X:TE, callable(X), \+ X = _:_,
    ( TE == t ; integer(TE) ; nonvar(TE), ( TE = T0+K ; TE = T0-K ), T0 == t, integer(K) ), !.

timed_call(X, T, W, info(_, DerT, _, _, _, _, _), Call) :-
    functor(X, N, A),
    (   memberchk(N/A, DerT)
    ->  X =.. [N|Args], derived_name(N, dt, DN),
        append(Args, [T, W], CArgs), Call =.. [DN|CArgs]
    ;   Call = ddc:'$undefined'(W, X:T)
    ).

prolog_callable(G) :-
    (   predicate_property(system:G, defined)
    ;   member(Lib, [lists, apply, aggregate, pairs, ordsets, error]),
        predicate_property(Lib:G, exported)
    ;   G = ddc_dist:_
    ), !.

%   read_key_code(+H, +Ctx, -X, -T, -TimeGoal)
read_key_code(H, _, _, _, _) :-
    var(H), !,
    throw(error(ddc(unbound_random_variable, query), _)).
read_key_code((X0:T0)+K, ctx(_, Tc, _, _), X, T, G) :- T0 == t, integer(K), !,
    X = X0, time_code(t+K, Tc, T, G).
read_key_code((X0:T0)-K, ctx(_, Tc, _, _), X, T, G) :- T0 == t, integer(K), !,
    X = X0, time_code(t-K, Tc, T, G).
read_key_code(X0:TE, ctx(_, Tc, _, _), X, T, G) :- !,
    X = X0, time_code(TE, Tc, T, G).
read_key_code(current(X0), ctx(_, Tc, _, _), X0, Tc, true) :- nonvar(X0), !.
read_key_code(next(X0), ctx(_, Tc, _, _), X0, T, (T is Tc+1)) :- nonvar(X0), !.
read_key_code(prior(X0), _, X0, 0, true) :- nonvar(X0), !.
read_key_code(X, ctx(_, Tc, Info, query), X, Tc, true) :-
    Info = info(_, _, RvU, RvT, _, _, _),
    callable(X), functor(X, N, A),
    memberchk(N/A, RvT), \+ memberchk(N/A, RvU), !.
read_key_code(X, _, X, u, true).

time_code(T, Tc, Tc, true) :- T == t, !.
time_code(N, _, N, true) :- integer(N), !.
time_code(E, Tc, T, (T is Tc+K)) :- nonvar(E), E = T0+K, T0 == t, integer(K), !.
time_code(E, Tc, T, (T is Tc-K)) :- nonvar(E), E = T0-K, T0 == t, integer(K), !.
time_code(V, _, V, true) :- var(V), !.
time_code(E, _, _, _) :-
    throw(error(ddc(bad_time(E), query), _)).

                 /*******************************
                 *            RUN TIME          *
                 *******************************/

%   A world:
%   w(Store, Module, Time, Frozen, Evidence, LogW, DX, QLogW, QDX, Acc,
%     Mode, Facts, Check, Shared, Pure)
%     Frozen: times =< Frozen are no longer derivable from earlier ones
%     (the filter's past); -1 for static queries.
%     Acc: argument index (6 or 8) of the log weight that likelihood
%     weighting currently adds to.
%     Mode: normal or sweep (non-ground reads enumerate recorded values only).
%     Facts: Name/Arity-[Fact, ...] groups of the facts asserted into W.
%     Check: true if overlapping clauses are checked in this world (the
%     first overlap_checked_worlds/1 samples of a query, the first
%     overlap_checked_particles/1 particles of each filter step; a check
%     proves the later clauses' bodies, so it is not done in every world).
%     Shared: none, or (a particle, during a filter step or query)
%     sh(SharedStore, ImpureKeys, _, _), the values all particles agree on
%     (see "Shared values" below).
%     Pure: true while the value being computed has read nothing of this
%     world's own and drawn nothing (false outside the filter).

new_world(M, Time, Frozen, Ev, W) :-
    new_world(M, Time, Frozen, Ev, true, W).

new_world(M, Time, Frozen, Ev, Check, W) :-
    store_new(S),
    W = w(S, M, Time, Frozen, Ev, 0.0, 0, 0.0, 0, 6, normal, [], Check, none, false).

/*  Shared values.  In a filter many values are the same in every particle:
    a value computed only from facts, observations and other shared values,
    with a deterministic distribution (val/1), is the same wherever it is
    computed.  Such a value is computed once per step, in whichever
    particle needs it first, and kept in the filter's shared store instead
    of every particle's own; other particles find it there.  A theory in
    which a perceived object's position is a val/1 of its observation (too.pl)
    then spends per-particle work only on what the particles disagree on.

    Each computation of a key (a random variable, a memoised or
    materialised derived atom) starts with Pure = true; reading a key from
    the world's own store, a non-ground read, a draw from a distribution
    other than val/1, or a likelihood weighting makes it false (the
    observations' values are in the shared store).  A pure value goes to
    the shared store unless the key is in ImpureKeys (some particle
    computed it from its own values, so the particles may differ), an
    impure one to the world's own store and ImpureKeys.  So a key is either shared or in the particles' own stores,
    never both, and a value read from the shared store is the value every
    particle would have computed.  A pure computation draws no random
    number, so sharing changes neither the draws nor any value: the
    particles are bit for bit those of computing everything in every
    particle (tests/prolog/test_ddc_shared.pl compares the two).  The
    weight an observation adds is shared the same way (key '$w'(X, T)), and
    so is a whole transition clause whose keys were all shared
    ('$swept'(Id, T), the sweep skips it).  At the end of a step, a value
    that all particles hold on their own but that came out the same in
    every one (an object seen again: wherever each particle had it, it is
    now where it was seen) moves to the shared store (share_agreed/4).
    Outside the filter (static queries) there is no shared store. */

%   known(+W, +K, -V): K's value in W, from its own store (which makes the
%   computation in progress impure) or the shared store.
known(W, K, V) :-
    arg(1, W, S),
    (   store_get(S, K, V0)
    ->  arg(15, W, P),
        (   P == false -> true ; nb_setarg(15, W, false) ),
        V = V0
    ;   arg(14, W, Sh),
        Sh \== none,
        arg(1, Sh, SS),
        store_get(SS, K, V)
    ).

%   shared_known(+W, +K): K is in W's shared store.
shared_known(W, K) :-
    arg(14, W, Sh),
    Sh \== none,
    arg(1, Sh, SS),
    store_get(SS, K, _).

impure(W) :-
    arg(15, W, P),
    (   P == false -> true ; nb_setarg(15, W, false) ).

%   begin_value(+W, -P0) ... end_value(+W, +P0, +K, +V): around the
%   computation of key K's value V; records it (shared or own, see above).
begin_value(W, P0) :-
    arg(15, W, P0),
    nb_setarg(15, W, true).

end_value(W, P0, K, V) :-
    arg(14, W, Sh),
    (   Sh == none
    ->  arg(1, W, S),
        store_put(S, K, V),
        nb_setarg(15, W, false)
    ;   arg(15, W, P),
        arg(2, Sh, Imp),
        (   P == true, arg(4, Sh, true), \+ store_get(Imp, K, _)
        ->  arg(1, Sh, SS),
            store_put(SS, K, V),
            nb_setarg(15, W, P0)
        ;   arg(1, W, S),
            store_put(S, K, V),
            (   store_get(Imp, K, _) -> true ; store_put(Imp, K, true) ),
            nb_setarg(15, W, false)
        )
    ).

'$live'(W, T) :-
    arg(4, W, Fz),
    T > Fz.

'$frozen_at'(W, T) :-
    arg(4, W, Fz),
    T =< Fz.

%!  '$read'(+X, +T, ?V, +W) is nondet.
%
%   V is the value of random variable X at time T (u: untimed) in W.
'$read'(X, T, V, W) :-
    (   ground(X)
    ->  read_key(X, T, V, W)
    ;   read_enum(X, T, V, W)
    ).

read_key(X, T, V, W) :-
    arg(1, W, S),
    (   store_get(S, X-T, Val)          % known/3, inline
    ->  arg(15, W, P),
        (   P == false -> true ; nb_setarg(15, W, false) ),
        Val \== '$undef'
    ;   arg(14, W, Sh), Sh \== none,
        arg(1, Sh, SS), store_get(SS, X-T, Val)
    ->  Val \== '$undef'
    ;   arg(5, W, Ev),                  % not yet read: evidence, or sampled
        (   Ev \== [], memberchk((X-T)-EV, Ev)
        ->  weigh_key(X, T, EV, W, 6),
            Val = EV
        ;   sample_key(X, T, W, Val)
        )
    ),
    (   Val = V -> true                 % match/2, inline
    ;   number(Val), number(V), Val =:= V
    ).

match(Val, V) :-
    (   Val = V -> true
    ;   number(Val), number(V), Val =:= V
    ).

sample_key(X, T, W, Val) :-
    arg(14, W, Sh),
    (   Sh == none                      % outside a filter: every value is the world's own
    ->  arg(2, W, M),
        arg(1, W, S),
        (   M:'$rv'(X, T, W, 0, none, Out, Tier, Id, R)
        ->  (   R == false -> true ; check_rivals(R, M, X, T, W, Tier, Id) ),
            draw(Out, W, Val),
            store_put(S, X-T, Val)
        ;   store_put(S, X-T, '$undef'),
            fail
        )
    ;   sample_shared(X, T, W, Val)
    ).

sample_shared(X, T, W, Val) :-
    arg(2, W, M),
    begin_value(W, P0),
    (   M:'$rv'(X, T, W, 0, none, Out, Tier, Id, R)
    ->  (   R == false -> true ; check_rivals(R, M, X, T, W, Tier, Id) ),
        (   deterministic(Out) -> true ; impure(W) ),
        draw(Out, W, Val),
        end_value(W, P0, X-T, Val)
    ;   end_value(W, P0, X-T, '$undef'),
        fail
    ).

deterministic(val(_)).
deterministic('$chk'(D, _)) :- nonvar(D), D = val(_).

%   Checking for overlapping clauses proves the rivals' bodies; what they
%   read does not make the value impure (it does not depend on them).
check_rivals(false, _, _, _, _, _, _) :- !.
check_rivals(true, M, X, T, W, Tier, Id) :-
    (   arg(13, W, true)
    ->  arg(15, W, P),
        (   M:'$rv'(X, T, W, Id, none, _, Tier, Id2, _)
        ->  nb_setarg(15, W, P),
            clause_where(M, Id2, Where2),
            key_term(X, T, K),
            '$clause_error'(W, Id, overlapping_clauses(K, Where2))
        ;   nb_setarg(15, W, P)
        )
    ;   true
    ).

key_term(X, u, X) :- !.
key_term(X, T, X:T).

draw('$chk'(D, Id), W, V) :- !,
    (   fast_valid(D)
    ->  dist_sample(D, V)
    ;   cheap_check(D)
    ->  checked(D, Id, W),
        dist_sample(D, V)
    ;   catch(dist_sample(D, V0), E, true),
        (   var(E), nonvar(V0) -> V = V0
        ;   checked(D, Id, W),          % throws the distribution's own error
            (   var(E) -> V = V0 ; throw(E) )
        )
    ).
draw(D, _, V) :-
    dist_sample(D, V).

%   Parameters are checked before each draw, except for the multivariate
%   Gaussians, whose check (a Cholesky factorisation) is the sampler's own
%   work: those are checked only when sampling raises an error.
cheap_check(D) :-
    (   var(D) -> true ; \+ expensive_check(D) ).    % unbound: checked/3 raises

%   Parameters valid by construction (a common case, tested inline).  A
%   distribution left unbound by its clause's body is not valid (checked/3
%   names the clause).
fast_valid(D) :- var(D), !, fail.
fast_valid(uniform(S)) :-
    (   S = A:C, integer(A), integer(C) -> C >= A
    ;   is_list(S), S \== []
    ).
fast_valid(val(_)).

expensive_check(gaussian(M, _)) :- is_list(M).
expensive_check(indepGaussians(_)).

checked(D, Id, W) :-
    var(D), !,
    '$clause_error'(W, Id, unbound_distribution).
checked(D, Id, W) :-
    catch(dist_check(D), error(ddc_distribution(D1, Why), _),
          '$clause_error'(W, Id, distribution(D1, Why))).

%   weigh_key(X, T, Value, W, Acc): likelihood weighting of X-T = Value
%   into the log weight at argument Acc of W (6 evidence, 8 query).  In a
%   filter step (Acc 6) a weight computed from shared values only is
%   shared: kept as '$w'(X, T) -> w(LogDensity, Dim) (or none: no clause).
%   A weighting makes the computation that needed it impure.
weigh_key(X, T, V, W, Acc) :-
    arg(14, W, Sh),
    (   Sh == none
    ->  weigh_own(X, T, V, W, Acc)
    ;   weigh_key_shared(X, T, V, W, Acc, Sh)
    ).

%   (Outside a filter.)
weigh_own(X, T, V, W, Acc) :-
    arg(1, W, S),
    (   weigh_clause(X, T, V, W, Acc, LP, K)
    ->  store_put(S, X-T, V),
        add_weight(W, Acc, LP, K)
    ;   store_put(S, X-T, '$undef'),
        fail
    ).

weigh_key_shared(X, T, V, W, Acc, Sh) :-
    arg(1, W, S),
    (   Acc == 6, arg(1, Sh, SS), store_get(SS, '$w'(X, T), Memo)
    ->  impure(W),
        Memo = w(LP, K),
        add_weight(W, Acc, LP, K)
    ;   begin_value(W, P0),
        (   weigh_clause(X, T, V, W, Acc, LP, K)
        ->  Memo = w(LP, K),
            (   shared_known(W, X-T) -> true ; store_put(S, X-T, V) )
        ;   Memo = none,
            (   shared_known(W, X-T) -> true ; store_put(S, X-T, '$undef') )
        ),
        (   Acc == 6 -> end_memo(W, P0, Sh, '$w'(X, T), Memo) ; true ),
        impure(W),
        Memo = w(_, _),
        add_weight(W, Acc, LP, K)
    ).

%   end_memo(+W, +P0, +Sh, +K, +Memo): shares Memo (an observation's
%   weight, a sweep's done marker) under key K if computed from shared
%   values only; no world keeps a copy of its own.
end_memo(W, P0, Sh, K, Memo) :-
    arg(15, W, P),
    arg(2, Sh, Imp),
    (   P == true, arg(4, Sh, true), \+ store_get(Imp, K, _)
    ->  arg(1, Sh, SS),
        store_put(SS, K, Memo)
    ;   store_get(Imp, K, _)
    ->  true
    ;   store_put(Imp, K, true)
    ),
    nb_setarg(15, W, P0).

%   weigh_clause(+X, +T, +V, +W, +Acc, -LogDensity, -Dim): the density of
%   X-T = V under its first applicable clause (Dim: the dimension of V for a
%   density, 0 for a probability mass).
weigh_clause(X, T, V, W, Acc, LP, K) :-
    arg(2, W, M),
    arg(10, W, Acc0),
    (   Acc0 == Acc -> true ; nb_setarg(10, W, Acc) ),
    (   M:'$rv'(X, T, W, 0, ev(V), Out, Tier, Id, R)
    ->  (   Acc0 == Acc -> true ; nb_setarg(10, W, Acc0) ),
        (   R == false -> true ; check_rivals(R, M, X, T, W, Tier, Id) ),
        (   Out = '$prop'(LJ)
        ->  LP = LJ, K = 0
        ;   Out = '$chk'(D, Id1)
        ->  (   fast_valid(D)
            ->  density(D, V, LP, K)
            ;   cheap_check(D)
            ->  checked(D, Id1, W), density(D, V, LP, K)
            ;   catch(density(D, V, LP, K), E, ( checked(D, Id1, W), throw(E) ))
            )
        ;   density(Out, V, LP, K)
        )
    ;   (   Acc0 == Acc -> true ; nb_setarg(10, W, Acc0) ),
        fail
    ).

density(D, V, LP, K) :-
    dist_log_density(D, V, LP),
    (   dist_discrete(D) -> K = 0 ; value_dim(V, K) ).

add_weight(W, Acc, LP, K) :-
    add_logw(W, Acc, LP),
    (   K == 0 -> true
    ;   DXi is Acc+1, arg(DXi, W, DX0), DX is DX0+K, nb_setarg(DXi, W, DX)
    ).

%   A zero weight (log -inf) does not fail the proof: it marks the world
%   dead, so that "no clause applies" and "weight 0" stay distinct.
add_logw(W, Acc, LP) :-
    arg(Acc, W, L0),
    (   LP > -inf, L0 > -inf -> L is L0 + LP
    ;   L is -inf
    ),
    nb_setarg(Acc, W, L).

value_dim(V, 1) :- number(V), !.
value_dim((_,B), K) :- !, value_dim(B, K0), K is K0+1.
value_dim(L, K) :- is_list(L), !, length(L, K).
value_dim(_, 1).

%   '$read_ev'(X, T, A, W): the evidence value A of X at T, propagated
%   from a val/1 clause.
'$read_ev'(X, T, A, W) :-
    ground(X),
    impure(W),
    arg(10, W, Acc),
    (   known(W, X-T, Val)
    ->  Val \== '$undef',
        (   match(Val, A) -> true ; NInf is -inf, add_logw(W, Acc, NInf) )
    ;   weigh_key(X, T, A, W, Acc)
    ).

%   '$read_q'(X, T, V, W): a top-level query literal: ground and not yet
%   sampled, it is weighted instead of sampled.
'$read_q'(X, T, V, W) :-
    (   ground(X), ground(V),
        arg(1, W, S), \+ store_get(S, X-T, _), \+ shared_known(W, X-T),
        arg(5, W, Ev), \+ memberchk((X-T)-_, Ev)
    ->  weigh_key(X, T, V, W, 8)
    ;   '$read'(X, T, V, W)
    ).

%   Non-ground random variable: the recorded groundings, and (unless
%   sweeping) those the clause bodies define.
read_enum(X, T, V, W) :-
    impure(W),                          % which keys a world holds is its own
    arg(1, W, S),
    findall(X-T, ( store_match(S, X-T, Val), Val \== '$undef' ), Rec0),
    (   arg(14, W, Sh), Sh \== none
    ->  arg(1, Sh, SS),
        findall(X-T, ( store_match(SS, X-T, Val), Val \== '$undef' ), Rec1),
        append(Rec0, Rec1, Rec)
    ;   Rec = Rec0
    ),
    (   arg(11, W, sweep)
    ->  Keys0 = Rec
    ;   arg(2, W, M),
        findall(X-T, M:'$rv'(X, T, W, 0, none, _, _, _, _), Def),
        append(Rec, Def, Keys0)
    ),
    sort(Keys0, Keys),
    member(X-T, Keys),
    read_key(X, T, V, W).

'$clause_error'(W, Id, Cause) :-
    arg(2, W, M),
    clause_where(M, Id, Where),
    throw(error(ddc(Cause, Where), _)).

clause_where(M, Id, File:Line) :-
    M:'$rv_pos'(Id, File, Line), !.
clause_where(M, _, M:0).

'$fact'(W, G) :-
    arg(12, W, Fs),
    is_list(Fs), Fs \== [],
    functor(G, N, A),
    memberchk(N/A-L, Fs),
    member(G, L).

%   '$undefined'(+World, +Goal): a call to a predicate the program does not
%   define: true for the facts of a filter step that match Goal.
'$undefined'(W, G) :-
    arg(12, W, Fs),
    (   Fs == static
    ->  undefined_in_static(G)
    ;   '$fact'(W, G)
    ).

%   static_world(!World): a world of a static query, which has no facts:
%   a predicate that the program does not define (read from the facts in
%   a filter) is an existence error there, named at the clause that calls
%   it (program_error/4), not a silent failure.
static_world(W) :-
    nb_setarg(12, W, static).

undefined_in_static(G) :-
    (   G = X:_ -> true ; X = G ),
    functor(X, N, A),
    existence_error(procedure, N/A).

%   group_facts(+Facts, -Groups): Name/Arity-[Fact, ...]
group_facts(Facts, Groups) :-
    findall(N/A-F, ( member(F, Facts), functor(F, N, A) ), Ps),
    keysort(Ps, Sorted),
    group_pairs_by_key(Sorted, Groups).

%!  overlap_checked_worlds(-N) is det.
%
%   Overlapping clauses are looked for in the first N sampled worlds of a
%   query (and in the first overlap_checked_particles/1 particles of every
%   filter step).
overlap_checked_worlds(200).

'$memo'(W, G, Call) :-
    arg(3, W, Tc),
    K = '$memo'(G, Tc),
    (   known(W, K, V)
    ->  V == true
    ;   arg(2, W, M),
        begin_value(W, P0),
        (   call(M:Call) -> V = true ; V = false ),
        (   known(W, K, _) -> impure(W) ; end_value(W, P0, K, V) ),
        V == true
    ).

%   '$shared'(+Key, ?Template, :Goal): the solutions of a clean derived
%   atom (clean_preds/3), computed once per filter step (or filter query)
%   for all particles and kept in a trie keyed by the variant of Key;
%   outside the filter (no shared table) Goal is simply called.
:- meta_predicate '$shared'(+, ?, 0).
'$shared'(Key, Tmpl, Goal) :-
    (   nb_current('$ddc_shared', Tr), Tr \== none
    ->  (   trie_lookup(Tr, Key, L)
        ->  true
        ;   findall(Tmpl, Goal, L),
            ( trie_insert(Tr, Key, L) -> true ; true )
        ),
        member(Tmpl, L)
    ;   call(Goal)
    ).

%   with_shared(:Goal): runs Goal with a fresh table of shared answers.
:- meta_predicate with_shared(0).
with_shared(Goal) :-
    (   nb_current('$ddc_shared', Old) -> true ; Old = none ),
    trie_new(Tr),
    nb_setval('$ddc_shared', Tr),
    call_cleanup(Goal, ( nb_setval('$ddc_shared', Old), trie_destroy(Tr) )).

'$mat'(W, G, T) :-
    functor(G, N, A),
    (   known(W, '$mat'(N/A, T), L)
    ->  true
    ;   arg(4, W, T),                   % the last frozen time only
        arg(2, W, M),
        once(( M:'$sweep'(der, K, N/A, Sw), Sw = sw(_, lazy, _, _, T, W),
               sweep_kind(K, T) )),
        lazy_materialise(W, M, N/A, Sw, T),
        known(W, '$mat'(N/A, T), L)
    ),
    member(G, L).

%   '$range'(+Lo, +Hi, -L): L = [Lo, ..., Hi], as findall(X, between(Lo, Hi,
%   X), L) (whose errors it keeps for non-integers) without its overhead.
'$range'(Lo, Hi, L) :-
    (   integer(Lo), integer(Hi)
    ->  range_(Lo, Hi, L)
    ;   findall(X, between(Lo, Hi, X), L)
    ).

range_(Lo, Hi, L) :-
    (   Lo > Hi
    ->  L = []
    ;   L = [Lo|T], Lo1 is Lo+1, range_(Lo1, Hi, T)
    ).

'$flip'(P) :-
    random_float < P.

'$sample_inline'(D0, X) :-
    (   needs_eval(D0) -> eval_dist(D0, D) ; D = D0 ),
    dist_sample(D, X).

                 /*******************************
                 *            QUERIES           *
                 *******************************/

%!  query(+Query, -P) is det.
%!  query(+Query, -P, +Options) is det.
%
%   P is the probability of Query (a goal, possibly a conjunction, possibly
%   time-indexed: `pos(1):3 > 0`) in the program loaded last, estimated
%   from 10,000 samples (option samples(N)).  See query/4.
query(Q, P) :-
    query(true, Q, P, []).
query(Q, P, Options) :-
    query(true, Q, P, Options).

%!  query(+Evidence, +Query, -P, +Options) is det.
%
%   P = P(Query | Evidence), by likelihood weighting.  Evidence is a goal,
%   a list of goals or `true`.  Options:
%     - samples(N): number of sampled worlds (default 10000)
%     - seed(S): set_random(seed(S)) first (same seed, same answer)
%     - stderr(-SE): the standard error of the estimate (delta method for
%       the self-normalised estimator)
%     - ess(-ESS): the effective sample size (sum w)^2 / sum w^2 of the
%       samples that count; ESS < N shows how much the evidence cost
%     - program(M): the program (default: the one loaded last)
%     - time(T): the time `t` means in the query (default 0); e.g.
%       query(left(1,2):t ~= true, P, [time(3)]) unrolls to time 3.
%   Throws error(ddc(zero_evidence(E), query), _) if the evidence has
%   weight 0 in every sample.
query(Ev, Q, P, Options) :-
    query_program(Options, M),
    ddc_query(M, Ev, Q, Options, P, Stats),
    Stats = stats(SE, ESS, _, _),
    option(stderr(SE), Options, _),
    option(ess(ESS), Options, _).

%!  query(+PosEv, +NegEv, +Query, +N, -P) is det.
%
%   The original system's form: PosEv a list of goals that hold, NegEv a
%   list of goals that do not (proven, unlike the original which only
%   looked them up among recorded facts), N samples.
query(PosEv, NegEv, Q, N, P) :-
    neg_evidence(PosEv, NegEv, Ev),
    query(Ev, Q, P, [samples(N)]).

%!  query(+PosEv, +NegEv, +Query, ?X, +N, -Avg, -SuccSum, -Sum) is det.
%
%   The original's expectation form: Avg = E[X * 1(Query) | evidence]
%   (SuccSum = sum of w*X over samples where Query holds, Sum = sum of
%   evidence weights).  With a Query that always holds it is E[X | e].
query(PosEv, NegEv, Q, X, N, Avg, SuccSum, Sum) :-
    neg_evidence(PosEv, NegEv, Ev),
    query_program([], M),
    ddc_run(M, Ev, Q, X, [samples(N)], value, R),
    R = r(Sum, _, SuccSum, _, _, _, _, _, _, _),
    Avg is SuccSum / Sum.

neg_evidence(PosEv, NegEv, Ev) :-
    must_be(list, PosEv), must_be(list, NegEv),
    findall(\+ G, member(G, NegEv), Negs),
    append(PosEv, Negs, Ev).

%!  expectation(+Evidence, +Query, ?X, -E, +Options) is det.
%
%   E = E[X | Evidence, Query]: the weighted mean of X (numeric, bound by
%   the first proof of Query) over the worlds where Query holds.  For
%   E[X | e] use a Query that binds X and always holds (`g ~= X`).  (The
%   original's query/8 divides by the evidence weight instead; query/8
%   keeps that.)  Options as query/4 (stderr(SE) is the standard error).
expectation(Ev, Q, X, E, Options) :-
    query_program(Options, M),
    ddc_run(M, Ev, Q, X, Options, value, R),
    R = r(_, _, SWY, _, SW2Y2, SWQ, _, _, SW2QY, SW2Q2),
    (   SWQ > 0 -> true ; throw(error(ddc(query_never_holds(Q), query), _)) ),
    E is SWY / SWQ,
    (   option(stderr(SE), Options)
    ->  SE is sqrt(max(0.0, SW2Y2 - 2*E*SW2QY + E*E*SW2Q2)) / SWQ
    ;   true
    ).

%!  distribution(+Evidence, +Query, ?X, -Dist, +Options) is det.
%
%   Dist = [P:Value, ...], the posterior distribution of X (bound by the
%   first proof of Query in each world), sorted by value; worlds where
%   Query fails are left out (Dist is conditioned on Query holding).
distribution(Ev, Q, X, Dist, Options) :-
    query_program(Options, M),
    ddc_run(M, Ev, Q, X, Options, dist, R),
    R = r(_, _, _, _, _, SWQ, Pairs, _, _, _),
    (   SWQ > 0 -> true ; throw(error(ddc(query_never_holds(Q), query), _)) ),
    findall(P:V, ( member(V-Wv, Pairs), P is Wv / SWQ ), Dist).

query_program(Options, M) :-
    (   option(program(M0), Options)
    ->  M = M0
    ;   current_program_(M0)
    ->  M = M0
    ;   throw(error(ddc(no_program_loaded, query), _))
    ).

%!  ddc_query(+Module, +Evidence, +Query, +Options, -P, -Stats) is det.
%
%   Stats = stats(StdErr, ESS, SamplesThatCount, Samples).
ddc_query(M, Ev, Q, Options, P, stats(SE, ESS, NPos, N)) :-
    option(samples(N), Options, 10000),
    ddc_run(M, Ev, Q, _, Options, prob, R),
    R = r(SW, SW2, SWY, SW2Y, SW2Y2, _, _, NPos, _, _),
    P is SWY / SW,
    SE is sqrt(max(0.0, SW2Y2 - 2*P*SW2Y + P*P*SW2)) / SW,
    ESS is SW*SW / SW2.

%!  ddc_query_text(+Module, +QueryText, +EvidenceText, +Samples, +Seed, -Result) is det.
%
%   For the Python bridge: the texts are parsed with the DC operators
%   (EvidenceText '' means no evidence; Seed `none` means do not reseed).
%   Result = [P, StdErr, ESS, Samples].  Errors are thrown as by query/4.
ddc_query_text(M, QT, ET, N, Seed, [P, SE, ESS, N]) :-
    text_goal(QT, Q),
    (   empty_text(ET) -> Ev = true ; text_goal(ET, Ev) ),
    (   Seed == none -> Opts = [samples(N)] ; Opts = [samples(N), seed(Seed)] ),
    ddc_query(M, Ev, Q, Opts, P, stats(SE, ESS, _, N)).

%!  ddc_expectation_text(+Module, +ValueText, +QueryText, +EvidenceText, +N, +Seed, -Result) is det.
%
%   Result = [E, StdErr, ESS, N] for E[Value | Evidence, Query]; the
%   texts share variables (Value is read together with Query).
ddc_expectation_text(M, XT, QT, ET, N, Seed, [E, SE, ESS, N]) :-
    format(string(Both), "(~w)-(~w)", [XT, QT]),
    text_goal(Both, X-Q),
    (   empty_text(ET) -> Ev = true ; text_goal(ET, Ev) ),
    (   Seed == none -> Opts = [samples(N)] ; Opts = [samples(N), seed(Seed)] ),
    expectation(Ev, Q, X, E, [stderr(SE), program(M)|Opts]),
    ESS = N.

%!  ddc_distribution_text(+Module, +ValueText, +QueryText, +EvidenceText, +N, +Seed, -Pairs) is det.
%
%   Pairs = [[P, ValueText], ...], the distribution of Value given
%   Evidence and Query, values written with writeq.
ddc_distribution_text(M, XT, QT, ET, N, Seed, Pairs) :-
    format(string(Both), "(~w)-(~w)", [XT, QT]),
    text_goal(Both, X-Q),
    (   empty_text(ET) -> Ev = true ; text_goal(ET, Ev) ),
    (   Seed == none -> Opts = [samples(N)] ; Opts = [samples(N), seed(Seed)] ),
    distribution(Ev, Q, X, D, [program(M)|Opts]),
    findall([P, VT], ( member(P:V, D), format(string(VT), "~q", [V]) ), Pairs).

empty_text(T) :- var(T), !.
empty_text('').
empty_text("").
empty_text(none).
empty_text('None').

text_goal(Text, G) :-
    check_text_nesting(Text, query),
    catch(term_string(G, Text, [module(ddc)]), error(syntax_error(E), _),
          ( format(atom(A), "~w", [Text]),
            throw(error(ddc(syntax_error(E), text(A)), _)) )).

%   ddc_run(+M, +Ev, +Q, ?X, +Options, +Mode, -R)
%   R = r(SW, SW2, SWY, SW2Y, SW2Y2, SWQ, Pairs, NPos) over the samples of
%   the smallest evidence dimension.
ddc_run(M, Ev0, Q, X, Options, Mode, R) :-
    (   program_file_(M, _) -> true
    ;   throw(error(ddc(unknown_program(M), query), _))
    ),
    option(samples(N), Options, 10000),
    must_be(positive_integer, N),
    option(time(Time), Options, 0),
    (   option(seed(Seed), Options) -> set_random(seed(Seed)) ; true ),
    evidence_goal(Ev0, EvG),
    M:'$ddc_info'(Info),
    prepare_query(M, Info, Time, EvG, Q, X, Ev, Id),
    call_cleanup(
        findall(S, ( between(1, N, I), one_sample(M, Id, Time, Ev, I, S) ), Samples),
        retractall(M:'$ddc_tmp'(Id, _, _, _))),
    (   Samples == []
    ->  throw(error(ddc(zero_evidence(Ev0), query), _))
    ;   true
    ),
    min_dx(Samples, 1000000000, MinDX),
    summarise(Mode, Samples, MinDX, R).

%   one_sample(+M, +Id, +Time, +Ev, -s(W, DX, QW, X)): fails when the
%   evidence fails or has weight 0; QW is 0.0 when the query fails.
one_sample(M, Id, Time, Ev, I, s(W, DX, QW, X)) :-
    overlap_checked_worlds(Checked),
    (   I =< Checked -> Check = true ; Check = false ),
    new_world(M, Time, -1, Ev, Check, Wd),
    static_world(Wd),
    M:'$ddc_tmp'(Id, s, Wd, Out),       % evidence, then the query (prepare_query/8)
    arg(6, Wd, LW),
    (   LW == 0.0 -> W = 1.0
    ;   LW > -inf, W is exp(LW), W > 0.0
    ),
    arg(7, Wd, DX),
    (   Out = q(X0)
    ->  arg(8, Wd, QLW),
        (   QLW == 0.0 -> QW = 1.0 ; exp_w(QLW, QW) ),
        X = X0
    ;   QW = 0.0, X = '$none'
    ).

%   '$ev_holds'(+W): the evidence proven so far has a weight above 0 (the
%   query is not proven in a world of weight 0).
'$ev_holds'(W) :-
    arg(6, W, LW),
    LW > -inf.

min_dx([], M, M).
min_dx([s(_, DX, _, _)|Ss], M0, M) :-
    (   DX < M0 -> min_dx(Ss, DX, M) ; min_dx(Ss, M0, M) ).

%   R = r(SW, SW2, SWY, SW2Y, SW2Y2, SWQ, Pairs, NPos, SW2QY, SW2Q2) over
%   the samples of dimension MinDX; Y = QW (prob), QW*X (value).
summarise(dist, Samples, MinDX, r(SW, 0.0, 0.0, 0.0, 0.0, SWQ, Pairs, NPos, 0.0, 0.0)) :- !,
    findall(X-WQ, ( member(s(W, MinDX, QW, X), Samples), QW > 0.0, WQ is W*QW ), XWs),
    msort(XWs, Sorted),
    group_pairs_by_key(Sorted, Groups),
    findall(X-S, ( member(X-Ws, Groups), sum_list(Ws, S) ), Pairs),
    aggregate_all(count, member(s(_, MinDX, _, _), Samples), NPos),
    aggregate_all(sum(W), member(s(W, MinDX, _, _), Samples), SW),
    aggregate_all(sum(V), member(_-V, Pairs), SWQ).
summarise(prob, Samples, MinDX, r(SW, SW2, SWY, SW2Y, SW2Y2, SWY, [], N, SW2Y, SW2Y2)) :- !,
    psums(Samples, MinDX, 0.0, 0.0, 0.0, 0.0, 0.0, 0, SW, SW2, SWY, SW2Y, SW2Y2, N).
summarise(Mode, Samples, MinDX, R) :-
    sums(Samples, Mode, MinDX, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0, 0.0, 0.0, R).

%   Probability: Y = QW.
psums([], _, SW, SW2, SWY, SW2Y, SW2Y2, N, SW, SW2, SWY, SW2Y, SW2Y2, N).
psums([s(W, DX, Y, _)|Ss], MinDX, A0, B0, C0, D0, E0, N0, A, B, C, D, E, N) :-
    (   DX =:= MinDX
    ->  W2 is W*W,
        A1 is A0 + W, B1 is B0 + W2,
        (   Y =:= 0.0
        ->  C1 = C0, D1 = D0, E1 = E0
        ;   C1 is C0 + W*Y, W2Y is W2*Y, D1 is D0 + W2Y, E1 is E0 + W2Y*Y
        ),
        N1 is N0 + 1,
        psums(Ss, MinDX, A1, B1, C1, D1, E1, N1, A, B, C, D, E, N)
    ;   psums(Ss, MinDX, A0, B0, C0, D0, E0, N0, A, B, C, D, E, N)
    ).

sums([], _, _, SW, SW2, SWY, SW2Y, SW2Y2, SWQ, N, SW2QY, SW2Q2,
     r(SW, SW2, SWY, SW2Y, SW2Y2, SWQ, [], N, SW2QY, SW2Q2)).
sums([s(W, DX, Q, X)|Ss], Mode, MinDX, SW0, SW20, SWY0, SW2Y0, SW2Y20, SWQ0, N0, A0, B0, R) :-
    (   DX =:= MinDX
    ->  sample_y(Mode, Q, X, Y),
        W2 is W*W,
        SW is SW0 + W, SW2 is SW20 + W2,
        SWY is SWY0 + W*Y, SW2Y is SW2Y0 + W2*Y, SW2Y2 is SW2Y20 + W2*Y*Y,
        SWQ is SWQ0 + W*Q, A is A0 + W2*Q*Y, B is B0 + W2*Q*Q,
        N is N0 + 1,
        sums(Ss, Mode, MinDX, SW, SW2, SWY, SW2Y, SW2Y2, SWQ, N, A, B, R)
    ;   sums(Ss, Mode, MinDX, SW0, SW20, SWY0, SW2Y0, SW2Y20, SWQ0, N0, A0, B0, R)
    ).

sample_y(prob, Q, _, Q).
sample_y(value, Q, X, Y) :-
    (   Q =:= 0.0 -> Y = 0.0
    ;   number(X) -> Y is Q*X
    ;   throw(error(ddc(not_a_number(X), query), _))
    ).

evidence_goal(V, _) :- var(V), !, instantiation_error(V).
evidence_goal([], true) :- !.
evidence_goal(L, G) :- is_list(L), !, conj_from_list(L, G).
evidence_goal(G, G).

%   Compile evidence and query into two temporary clauses of M; `t` is
%   the query time.
prepare_query(M, Info, Time, EvG, Q, X, Ev, Id) :-
    flag(ddc_query_id, Id, Id+1),
    copy_term(EvG, EvG1),
    Ctx = ctx(W, Time, Info, query),
    conj_list(EvG1, EvLs),
    evidence_map(EvLs, Ctx, Ev),
    cb(EvG1, Ctx, EvCode),
    Ctx2 = ctx(W, Time, Info, query),
    copy_term(Q-X, Q2-X2),
    conj_list(Q2, QLs),
    maplist(query_literal(Ctx2), QLs, QCodes),
    conj_from_list(QCodes, QCode),
    %   one call per sample: the first proof of the evidence, then the query
    %   (Out = q(X) when it holds, none when it fails)
    optimised(assertz(M:('$ddc_tmp'(Id, s, W, Out) :-
                            EvCode, !,
                            (   ddc:'$ev_holds'(W), QCode
                            ->  Out = q(X2)
                            ;   Out = none
                            )))).

%   Ground top-level evidence literals h ~= v are weighted, not sampled.
evidence_map(Ls, Ctx, Ev) :-
    findall((X-T)-V,
            ( member(L, Ls), nonvar(L), L = (H ~= V), ground(H), ground(V),
              read_key_code(H, Ctx, X, T, TG), call(TG), ground(X-T) ),
            Ev).

query_literal(Ctx, G, Code) :-
    nonvar(G), G = (H ~= V), \+ var(V), !,     % a value that may be ground: weighted
    read_key_code(H, Ctx, X, T, TG),
    Ctx = ctx(W, _, _, _),
    Code = (TG, ddc:'$read_q'(X, T, V, W)).
query_literal(Ctx, G, Code) :-
    cb(G, Ctx, Code).

exp_w(L, W) :-
    (   L == 0.0 -> W = 1.0
    ;   L =:= -inf -> W = 0.0
    ;   W is exp(L)
    ).

%!  ddc_sample_world(+Module, +Query, +Options, -Facts) is semidet.
%
%   Proves Query in one sampled world (option time(T), seed(S)) and
%   returns what the world holds as Key-Value pairs (the original's
%   generate_backward).  Options values(Vs) (X-Time-Value triples) and
%   facts(Fs) (atoms, as a filter step's actions) are put into the world
%   first; with facts, a predicate the program does not define is looked
%   up among them, as in a filter step.
ddc_sample_world(M, Q, Options, Facts) :-
    option(time(Time), Options, 0),
    option(values(Vs), Options, []),
    option(facts(Fs), Options, []),
    must_be(list, Vs), must_be(list, Fs),
    (   option(seed(Seed), Options) -> set_random(seed(Seed)) ; true ),
    M:'$ddc_info'(Info),
    new_world(M, Time, -1, [], W),
    (   Fs == [] -> static_world(W) ; group_facts(Fs, Gs), nb_setarg(12, W, Gs) ),
    arg(1, W, S0),
    forall(member(X-T-V, Vs), store_put(S0, X-T, V)),
    Ctx = ctx(W, Time, Info, query),
    cb(Q, Ctx, Code),
    once(M:Code),
    arg(1, W, S),
    store_entries(S, Facts).

                 /*******************************
                 *      ERRORS AT RUN TIME      *
                 *******************************/

%   An error raised while a program's clause runs (division by zero, a type
%   error, throw/1 of the program, an undefined procedure) is turned into
%   error(ddc(prolog_error(E), File:Line), _) naming the innermost clause of
%   a program between where it was raised and where it is caught.  Nothing
%   is paid when no exception is raised: the clause is found from the
%   frames at that moment (program_error/4) and the table of the program's
%   clause references and lines ('$clause_line'/2, written at load).  An
%   exception caught inside the program's own clause (its catch/3) is left
%   as it is, as are the engine's own errors.

:- multifile prolog:prolog_exception_hook/5.
:- dynamic prolog:prolog_exception_hook/5.

install_exception_hook :-
    Head = prolog:prolog_exception_hook(E0, E, Frame, Catcher, _),
    (   clause(Head, ddc:program_error(E0, E, Frame, Catcher))
    ->  true
    ;   asserta((Head :- ddc:program_error(E0, E, Frame, Catcher)))
    ).

:- initialization(install_exception_hook).

%!  program_error(+Error, -ProgramError, +Frame, +Catcher) is semidet.
program_error(E0, E, Frame, Catcher) :-
    \+ engine_error(E0),
    \+ caught_by_program(Catcher),
    program_frame(Frame, Catcher, 200, M, Ref),
    M:'$clause_line'(Ref, Line),
    program_file_(M, File), !,
    E = error(ddc(prolog_error(E0), File:Line), _).

engine_error(E) :- var(E), !.
engine_error(error(ddc(_, _), _)).
engine_error(error(ddc_distribution(_, _), _)).
engine_error('$aborted').
engine_error(unwind(_)).
engine_error(time_limit_exceeded).

%   caught_by_program(+Catcher): the catch/3 that will catch the error is
%   called by a clause of a program (its own catch/3, whose catcher may ask
%   for the error as Prolog raised it).
caught_by_program(Catcher) :-
    integer(Catcher),
    (   F = Catcher ; prolog_frame_attribute(Catcher, parent, F) ),
    prolog_frame_attribute(F, predicate_indicator, M:_),
    program_file_(M, _), !.

%   program_frame(+Frame, +Catcher, +Depth, -Module, -ClauseRef): the first
%   frame from Frame up (and below the catcher's frame) running a clause of
%   a loaded program.
program_frame(Frame, Catcher, D, M, Ref) :-
    integer(Frame), Frame \== Catcher, D > 0,
    (   prolog_frame_attribute(Frame, clause, Ref0),
        prolog_frame_attribute(Frame, predicate_indicator, M0:_),
        program_file_(M0, _)
    ->  M = M0, Ref = Ref0
    ;   prolog_frame_attribute(Frame, parent, Parent),
        D1 is D-1,
        program_frame(Parent, Catcher, D1, M, Ref)
    ).

                 /*******************************
                 *            MESSAGES          *
                 *******************************/

prolog:message(error(ddc(Cause, Where), _)) -->
    where(Where),
    cause(Cause).

where(File:Line) --> { integer(Line) }, !, [ '~w:~w: '-[File, Line] ].
where(text(T)) --> !, [ 'in "~w": '-[T] ].
where(query) --> !, [ 'query: ' ].
where(nowhere) --> !, [].
where(W) --> [ '~w: '-[W] ].

cause(syntax_error(M)) --> !, [ 'syntax error: ~w'-[M] ].
cause(distribution(D, Why)) --> !,
    (   { string(Why) } -> [ '~w'-[Why] ]
    ;   prolog:message(ddc_distribution(D, Why))
    ->  []
    ;   [ 'invalid distribution ~p: ~p'-[D, Why] ]
    ).
cause(non_ground_head(H)) --> !,
    [ 'the head ~p is not ground after its body was proven'-[H] ].
cause(overlapping_clauses(K, Other)) --> !,
    [ 'two clauses define ~p in the same world: this one and the one at ~w (make the bodies exclusive, or declare :- first_applicable(Name/Arity) to take the first)'-[K, Other] ].
cause(zero_evidence(E)) --> !,
    [ 'the evidence ~p has weight 0 in every sample (impossible evidence, or too few samples)'-[E] ].
cause(no_observation_clause(O)) --> !,
    [ 'no clause applies to the observation ~p'-[O] ].
cause(no_such_file(F)) --> !, [ 'no such file ~w'-[F] ].
cause(bad_directive(D)) --> !, [ 'unknown directive ~p'-[D] ].
cause(bad_head(H)) --> !,
    [ 'not a clause head: ~p (a random variable is defined by ~~ or :=, e.g. h:t+1 := true)'-[H] ].
cause(fresh_arithmetic) --> !,
    [ 'arithmetic (is/2 or a comparison) reads a variable that nothing before it binds' ].
cause(unbound_head) --> !, [ 'the clause head is a variable' ].
cause(unbound_body) --> !, [ 'the directive or clause body is a variable' ].
cause(unknown_program(M)) --> !, [ 'no DC program ~p is loaded'-[M] ].
cause(no_program_loaded) --> !, [ 'no DC program is loaded (use ddc_load/1)' ].
cause(query_never_holds(Q)) --> !, [ 'the query ~p never holds in a sample that counts'-[Q] ].
cause(not_a_number(X)) --> !, [ 'the expectation needs a number, got ~p'-[X] ].
cause(unknown_filter(F)) --> !, [ 'no filter ~p (freed, or never created)'-[F] ].
cause(bad_indices(Why)) --> !, [ 'bad resampling indices: ~w'-[Why] ].
cause(nothing_to_undo) --> !, [ 'no step to undo' ].
cause(batched_unsupported(What)) --> !,
    [ 'outside what the batched filter evaluates (use engine per_particle): ~p'-[What] ].
cause(not_ground(X)) --> !, [ 'not ground: ~p'-[X] ].
cause(bad_time(E)) --> !, [ 'bad time expression ~p (use t, t+K, t-K or an integer)'-[E] ].
cause(zero_arity_compound(Z)) --> !,
    { compound_name_arity(Z, Name, 0) },
    [ '~q has no arguments: write ~q or give it arguments'-[Z, Name] ].
cause(undefined_predicate(N/A)) --> !,
    [ '~q/~w is called here but defined nowhere in the program: in a filter it holds for the facts of a step, in a static query it is false (declare it with :- dynamic(~q/~w) to say it comes from facts)'-[N, A, N, A] ].
cause(too_deep(Max)) --> !,
    [ 'brackets nest deeper than ~D, the most the reader takes'-[Max] ].
cause(left_recursion(H)) --> !,
    [ 'the body of ~p starts by proving ~p itself: its proof would not end (remove the clause)'-[H, H] ].
cause(unbound_distribution) --> !,
    [ 'the distribution is unbound after the clause body was proven (x ~~ D := Body must bind D)' ].
cause(prolog_error(E)) -->
    { E = error(_, _) }, !,
    '$messages':translate_message(E).
cause(prolog_error(E)) --> !, [ 'the program threw ~p'-[E] ].
cause(unbound_random_variable) --> !, [ 'a random variable term is unbound' ].
cause(C) --> [ '~p'-[C] ].

:- include(ddc_filter).
