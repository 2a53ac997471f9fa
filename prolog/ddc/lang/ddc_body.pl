/*  ddc_body.pl -- compiling the bodies of DC clauses.

    Part of the DDC system (ddc.pl is the module users load).  Turns a
    clause body, a query or evidence (DC literals, derived atoms, Prolog
    goals) into the Prolog goal that proves it in a world: reads of random
    variables become calls of the world runtime (ddc_world.pl), derived
    atoms calls of their dispatchers in the program's module.
*/

:- module(ddc_body,
          [ compile_body/3,             % +Goal, +Context, -Code
            read_key_code/5,            % +Term, +Context, -X, -T, -TimeGoal
            invert_val_body/6,          % +Body, +V, +Context, -EvVal, -LogJacobian, -Code
            reset_undefined/0,
            warn_undefined/0,
            derived_name/3,             % +Name, +Kind, -DispatcherName
            conj_list/2,                % +Conjunction, -Goals
            conj_from_list/2,           % +Goals, -Conjunction
            occurs_in/2                 % +Var, +Term
          ]).

:- use_module(library(lists)).
:- use_module(library(error)).
:- use_module(ddc_records).
:- use_module(ddc_models, []).

:- use_module(ddc_ops).

%   Arithmetic compiled to virtual-machine instructions (local to this
%   file; see ddc.pl).
:- set_prolog_flag(optimise, true).

/** <module> Compiling DC clause bodies

A program's information, kept by the compiler (ddc_compile.pl) and read
when a body is compiled, is the record

    info(DerivedUntimed, DerivedTimed, RvsUntimed, RvsTimed, Plain, Impure,
         FirstApplicable)

(fields derived_untimed, derived_timed, rvs_untimed, rvs_timed, plain,
impure, first_applicable): the Name/Arity of the derived predicates and
random variables without and with a time index, of the plain Prolog
predicates, the memoised (impure) and shared (clean(...)) derived
predicates with the facts a filter step defines (fact(PI)), and the
first_applicable/1 declarations.

A body is compiled in a context ctx(World, Now, Info, Kind) (fields world,
now, info, kind): the variable that holds the world at run time, the
variable or integer that is the clause's current time `t`, the program's
info, and clause or query (in a query, an untimed read of a variable only
defined with a time index means its value at the current time).
*/

:- record_type info(derived_untimed, derived_timed, rvs_untimed, rvs_timed,
                    plain, impure, first_applicable).
:- record_type ctx(world, now, info, kind).

%!  derived_name(+Name, +Kind, -DispatcherName) is det.
%
%   The name of the predicate of kind Kind (d, d0, ds, dt, dt0, dt1, dt2,
%   dts) that a program module defines for derived predicate Name.
derived_name(N, Kind, Name) :-
    atomic_list_concat(['$', Kind, ':', N], Name).

%!  compile_body(+Goal, +Context, -Code) is det.
%
%   Code proves Goal (a clause body or a query) in the world of Context.

compile_body(G, _, call(G)) :- var(G), !.
compile_body(true, _, true) :- !.
compile_body((A,B), C, (CA,CB)) :- !, compile_body(A, C, CA), compile_body(B, C, CB).
compile_body((A;B), C, (CA;CB)) :- !, compile_body(A, C, CA), compile_body(B, C, CB).
compile_body((A->B), C, (CA->CB)) :- !, compile_body(A, C, CA), compile_body(B, C, CB).
compile_body((A*->B), C, (CA*->CB)) :- !, compile_body(A, C, CA), compile_body(B, C, CB).
compile_body(\+ A, C, \+ CA) :- !, compile_body(A, C, CA).
compile_body(once(A), C, once(CA)) :- !, compile_body(A, C, CA).
compile_body(ignore(A), C, ignore(CA)) :- !, compile_body(A, C, CA).
compile_body(forall(A,B), C, forall(CA,CB)) :- !, compile_body(A, C, CA), compile_body(B, C, CB).
compile_body(findall(T,G,L), _, Code) :-              % peephole: a range of integers
    var(T), nonvar(G), G = between(Lo, Hi, T1), T1 == T,
    \+ occurs_in(T, Lo-Hi), !,
    Code = ( Lo1 is Lo, Hi1 is Hi,
             ( integer(Lo1), integer(Hi1) -> ddc_world:range_(Lo1, Hi1, L) ; ddc_world:'$range'(Lo1, Hi1, L) ) ).
compile_body(findall(T,G,L), C, findall(T,CG,L)) :- !, compile_body(G, C, CG).
compile_body(findall(T,G,L,R), C, findall(T,CG,L,R)) :- !, compile_body(G, C, CG).
compile_body(findall_forward(T,G,L), C, findall(T,CG,L)) :- !, compile_body(G, C, CG).
compile_body(aggregate_all(S,G,R), C, aggregate_all(S,CG,R)) :- !, compile_body(G, C, CG).
compile_body(H ~= V, C, Code) :- !,
    read_key_code(H, C, X, T, TG),
    ctx_world(C, W),
    (   ground(X)
    ->  Code = (TG, ddc_world:read_key(X, T, V, W))
    ;   Code = (TG, ddc_world:'$read'(X, T, V, W))
    ).
compile_body(true(P), _, ddc_world:'$flip'(P)) :- !.
compile_body(sample(D, X), _, ddc_world:'$sample_inline'(D, X)) :- !.
compile_body(belief(A), _, ground(A)) :- !.
compile_body(timestep(T), C, (T = Now)) :- !,
    ctx_now(C, Now).
compile_body(G, _, ddc_models:G) :-                   % logistic/3, linear/3, softmax/3, mean_list/2, ...
    callable(G), predicate_property(ddc_models:G, exported), !.
compile_body(G, C, Code) :-
    compound(G), functor(G, Op, 2), memberchk(Op, [<, >, =<, >=, =:=, =\=]),
    G =.. [Op, A, B],
    ( rv_operand(A) ; rv_operand(B) ), !,
    operand_code(A, C, A1, CA),
    operand_code(B, C, B1, CB),
    G1 =.. [Op, A1, B1],
    Code = (CA, CB, G1).
compile_body(G, C, Code) :-
    timed_atom(G, X, TE), !,
    ctx_world(C, W), ctx_now(C, Now), ctx_info(C, Info), ctx_kind(C, Kind),
    time_code(TE, Now, T, TG),
    timed_call(X, T, W, Info, Call0),
    (   Kind \== query, Call0 = ddc_world:'$undefined'(W, XT)
    ->  functor(X, N, A), note_undefined(N/A, Info),
        Call = ddc_world:'$fact'(W, XT)
    ;   Call = Call0
    ),
    Code = (TG, Call).
compile_body(G, C, Code) :-
    callable(G), !,
    ctx_world(C, W), ctx_now(C, Now), ctx_info(C, Info), ctx_kind(C, Kind),
    functor(G, N, A),
    info_derived_untimed(Info, DerU), info_derived_timed(Info, DerT), info_plain(Info, Plain),
    (   memberchk(N/A, DerU)
    ->  G =.. [N|Args], derived_name(N, d, DN), append(Args, [W], CArgs), Code =.. [DN|CArgs]
    ;   Kind == query, memberchk(N/A, DerT)
    ->  timed_call(G, Now, W, Info, Code)
    ;   memberchk(N/A, Plain)
    ->  Code = G
    ;   prolog_callable(G)
    ->  Code = G
    ;   Kind == query
    ->  Code = ddc_world:'$undefined'(W, G)
    ;   note_undefined(N/A, Info),
        Code = ddc_world:'$fact'(W, G)
    ).

compile_body(G, _, _) :-
    type_error(callable, G).

%   note_undefined(+PI, +Info): a body calls PI, which the program defines
%   nowhere and does not declare (`:- dynamic(PI).`, the predicates a
%   filter step's facts define): remembered with the line of the clause
%   being compiled (global variable ddc_compiling), for the warning of
%   warn_undefined/0.
:- thread_local undefined_call_/2.

%!  reset_undefined is det.
%
%   Forgets the undefined predicates noted so far (before a program is
%   compiled).
reset_undefined :-
    retractall(undefined_call_(_, _)).

note_undefined(PI, Info) :-
    info_impure(Info, Impure),
    (   memberchk(fact(PI), Impure) -> true
    ;   undefined_call_(PI, _) -> true
    ;   nb_current(ddc_compiling, Where), Where \== []
    ->  assertz(undefined_call_(PI, Where))
    ;   true
    ).

%!  warn_undefined is det.
%
%   One warning per predicate called in the program's
%   bodies and defined nowhere: it holds only for the facts of a filter
%   step, and is false in a static query.
warn_undefined :-
    forall(retract(undefined_call_(PI, Where)),
           print_message(warning, error(ddc(undefined_predicate(PI), Where), _))).


rv_operand(X) :- nonvar(X), X = _:_, \+ number(X).
rv_operand(X) :- nonvar(X), X = (Y:_)+_, nonvar(Y).

operand_code(A, C, V, Code) :-
    rv_operand(A), !,
    compile_body(A ~= V, C, Code).
operand_code(A, _, A, true).

timed_atom(G, X, TE) :- compound(G), G = (X0:T0)+K, T0 == t, integer(K), callable(X0), !, X = X0, TE = t+K.
timed_atom(G, X, TE) :- compound(G), G = (X0:T0)-K, T0 == t, integer(K), callable(X0), !, X = X0, TE = t-K.
timed_atom(G, X, TE) :- compound(G), G = X:TE, callable(X), \+ X = _:_,
    ( TE == t ; integer(TE) ; nonvar(TE), ( TE = T0+K ; TE = T0-K ), T0 == t, integer(K) ), !.

timed_call(X, T, W, Info, Call) :-
    info_derived_timed(Info, DerT),
    functor(X, N, A),
    (   memberchk(N/A, DerT)
    ->  X =.. [N|Args], derived_name(N, dt, DN),
        append(Args, [T, W], CArgs), Call =.. [DN|CArgs]
    ;   Call = ddc_world:'$undefined'(W, X:T)
    ).

prolog_callable(G) :-
    (   predicate_property(system:G, defined)
    ;   member(Lib, [lists, apply, aggregate, pairs, ordsets, error]),
        predicate_property(Lib:G, exported)
    ;   G = ddc_dist:_
    ), !.

%!  read_key_code(+H, +Context, -X, -T, -TimeGoal) is det.
%
%   H, a random variable term as a body reads it (h:t+1, h:3, current(h),
%   an untimed h, ...), is random variable X at time T (u: untimed) once
%   TimeGoal has run.
read_key_code(H, _, _, _, _) :-
    var(H), !,
    throw(error(ddc(unbound_random_variable, query), _)).
read_key_code((X0:T0)+K, C, X, T, G) :- T0 == t, integer(K), !,
    ctx_now(C, Now), X = X0, time_code(t+K, Now, T, G).
read_key_code((X0:T0)-K, C, X, T, G) :- T0 == t, integer(K), !,
    ctx_now(C, Now), X = X0, time_code(t-K, Now, T, G).
read_key_code(X0:TE, C, X, T, G) :- !,
    ctx_now(C, Now), X = X0, time_code(TE, Now, T, G).
read_key_code(current(X0), C, X0, Now, true) :- nonvar(X0), !,
    ctx_now(C, Now).
read_key_code(next(X0), C, X0, T, (T is Now+1)) :- nonvar(X0), !,
    ctx_now(C, Now).
read_key_code(prior(X0), _, X0, 0, true) :- nonvar(X0), !.
read_key_code(X, C, X, Now, true) :-
    ctx_kind(C, query), ctx_now(C, Now), ctx_info(C, Info),
    info_rvs_untimed(Info, RvU), info_rvs_timed(Info, RvT),
    callable(X), functor(X, N, A),
    memberchk(N/A, RvT), \+ memberchk(N/A, RvU), !.
read_key_code(X, _, X, u, true).

time_code(T, Now, Now, true) :- T == t, !.
time_code(N, _, N, true) :- integer(N), !.
time_code(E, Now, T, (T is Now+K)) :- nonvar(E), E = T0+K, T0 == t, integer(K), !.
time_code(E, Now, T, (T is Now-K)) :- nonvar(E), E = T0-K, T0 == t, integer(K), !.
time_code(V, _, V, true) :- var(V), !.
time_code(E, _, _, _) :-
    throw(error(ddc(bad_time(E), query), _)).

%!  invert_val_body(+Body, +V, +Context, -EvVal, -LogJacobian, -Code) is semidet.
%
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
    ctx_world(Ctx, W),
    conj_from_list(Before, BB), conj_from_list(After, BA),
    compile_body(BB, Ctx, CB), compile_body(BA, Ctx, CA),
    read_key_code(R, Ctx, X, T, TG),
    InvCode = ( CB, InvGoal, TG, ddc_world:'$read_ev'(X, T, A, W), CA, LJGoal ).

%!  occurs_in(+Var, +Term) is semidet.
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

%!  conj_list(+Conjunction, -Goals) is det.
conj_list(V, [V]) :- var(V), !.
conj_list((A,B), L) :- !, conj_list(A, LA), conj_list(B, LB), append(LA, LB, L).
conj_list(true, []) :- !.
conj_list(G, [G]).

%!  conj_from_list(+Goals, -Conjunction) is det.
conj_from_list([], true).
conj_from_list([G], G) :- !.
conj_from_list([G|Gs], (G, C)) :- conj_from_list(Gs, C).
