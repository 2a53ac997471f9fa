/*  plunit tests of loading large programs (prolog/ddc.pl, rivals_table/3
    and clean_preds/3): the compiled program is the one of the definitions
    (every later clause compared with every earlier one, a fixpoint over
    the whole call graph), and the work of loading grows linearly with the
    number of clauses (counted in inferences, not timed).
*/
:- use_module('../../prolog/ddc').
:- use_module(library(plunit)).
:- use_module(library(lists)).
:- use_module(library(apply)).
:- use_module(library(ordsets)).

%   Every kind of head: untimed, h:t, h:t+1, h:0, h:N, persistent and
%   first_applicable variables, heads that unify or not, derived atoms
%   calling random ones through a chain, clean ones, unit ones.
kinds_program(File) :-
    tmp_file_stream(text, File, S),
    forall(member(L,
        [ ':- persistent(kept/1).',
          ':- first_applicable(fa/1).',
          'object(a) := true.', 'object(b) := true.',
          'big(A) := object(A), A == a.',
          'u(a) ~ val(1).', 'u(X) ~ val(2) := object(X).', 'u(b) ~ val(3).',
          'w(f(a, B)) ~ val(B) := object(B).', 'w(f(b, _)) ~ val(0).', 'w(g) ~ val(1).',
          'fa(X) ~ val(1) := object(X).', 'fa(a) ~ val(2).',
          'kept(X):t+1 ~ val(1) := object(X).',
          'p(X):t+1 ~ gaussian(0, 1) := object(X).',
          'p(a):2 ~ val(5).', 'p(a):0 ~ val(0).', 'p(X):0 ~ val(1) := object(X).',
          'p(b):3 ~ val(7).', 'p(a):t+1 ~ val(4).',
          'q(X):t ~ val(0) := object(X).', 'q(a):t ~ val(1).',
          'r(X):1 ~ val(1) := object(X).', 'r(a):(-1) ~ val(2).', 'r(a):1 ~ val(3).',
          'coin ~ finite([0.5:h, 0.5:t]).',
          'flip := coin ~= h.',
          'chain1 := flip.', 'chain2 := chain1.', 'chain3 := chain2, big(a).',
          'lucky := true(0.5).', 'lucky2 := lucky.',
          'near(X):t+1 := p(X):t+1 ~= V, V > 0.', 'far(X):t+1 := near(X):t+1.',
          'steady(X):t+1 := object(X).'
        ]),
        format(S, "~w~n", [L])),
    close(S).

shipped_program(File) :-
    Shipped = [ 'prolog/too.pl', 'prolog/too_learned.pl', 'prolog/too_learned_hindsight.pl',
                'prolog/examples/church.pl', 'prolog/examples/example1.pl',
                'prolog/examples/graph.pl', 'prolog/examples/indian_gpa.pl',
                'prolog/examples/paper_objects.pl', 'prolog/examples/tutorial.pl',
                'prolog/examples/filter/follow_the_occluder.pl',
                'prolog/examples/filter/pit_world.pl',
                'prolog/examples/filter/random_walk.pl', 'prolog/examples/filter/wumpus.pl',
                'prolog/examples/learn/occluder_generator.pl' ],
    member(Rel, Shipped),
    root_file(Rel, File).

root_file(Rel, Abs) :-
    source_file(kinds_program(_), Here),
    file_directory_name(Here, Dir),
    atomic_list_concat([Dir, '/../../', Rel], Abs0),
    absolute_file_name(Abs0, Abs).

%   The definition of rivals: compare a clause with every later one.
reference_rivals(Items, First, Id, R) :-
    member(rv(Id, X, K, _, _, _), Items),
    functor(X, N, A),
    (   ( K == persist ; memberchk(all, First) ; memberchk(N/A, First) )
    ->  R = false
    ;   member(rv(Id2, X2, K2, _, _, _), Items), Id2 > Id, K2 \== persist,
        tier(K2, T), tier(K, T), \+ X2 \= X, overlap(K, K2)
    ->  R = true
    ;   R = false
    ).

tier(state, 2) :- !.
tier(_, 1).

overlap(K, K) :- !.
overlap(trans, fixed(N)) :- N >= 1.
overlap(fixed(N), trans) :- N >= 1.

%   The definition of the closure: add callers of the set until none is new.
reference_closure(S0, Edges, S) :-
    findall(K, ( member(K-Cs, Edges), \+ memberchk(K, S0), member(C, Cs), memberchk(C, S0) ),
            New0),
    sort(New0, New),
    (   New == [] -> S = S0 ; ord_union(S0, New, S1), reference_closure(S1, Edges, S) ).

is_rivals(rivals(_, _)).
is_key(_/_/_).

%   The definition of a body that depends on the particle.
reference_dirty(B, _) :- ddc_compile:body_call(B, '$var'), !.
reference_dirty(B, _) :- ddc_compile:body_call(B, u/N/_), ( N == call ; sub_atom(N, _, _, _, random) ), !.
reference_dirty(B, Rvs) :-
    sub_term(S, B), nonvar(S),
    (   S = (_ ~= _)
    ;   S = true(_)
    ;   S = sample(_, _)
    ;   S = X:_, nonvar(X), callable(X), functor(X, N, A), memberchk(N/A, Rvs)
    ;   callable(S), functor(S, N, A), memberchk(N/A, Rvs)
    ), !.

check_program(File) :-
    ddc_load(File, M),
    ddc_programs:program_items(M, All),
    M:'$ddc_info'(info(_, _, _, _, _, Impure, First)),
    exclude(is_rivals, All, Items),
    findall(rivals(Id, R), reference_rivals(Items, First, Id, R), Expected),
    include(is_rivals, All, Got),
    assertion(Got == Expected),
    %   the memoised (impure) and the clean derived predicates
    findall(K-Calls, ( member(der(_, X, Kind, B, _), Items), functor(X, N, A),
                       ( Kind == u -> TK = u ; TK = t ), K = TK/N/A,
                       ddc_compile:body_calls(B, Calls) ), Edges),
    findall(K, ( member(K-Cs, Edges), memberchk(random, Cs) ), Seed0),
    sort(Seed0, Seed),
    reference_closure(Seed, Edges, ImpureKs),
    include(is_key, Impure, GotImpure),
    assertion(GotImpure == ImpureKs),
    findall(K, ( member(der(_, X, Kind, B, _), Items), functor(X, N, A),
                 ( Kind == u -> TK = u ; TK = t ), K = TK/N/A,
                 M:'$ddc_info'(info(_, _, RvU, RvT, _, _, _)), append(RvU, RvT, Rvs),
                 reference_dirty(B, Rvs) ), Dirty0),
    sort(Dirty0, DirtySeed),
    reference_closure(DirtySeed, Edges, Dirty),
    findall(K, member(K-_, Edges), Ks0), sort(Ks0, Ks),
    ord_subtract(Ks, Dirty, Clean),
    findall(K, member(clean(K), Impure), GotClean),
    assertion(GotClean == Clean),
    %   the sweep reads each distinct key of the transition clauses once
    M:'$ddc_info'(Info),
    findall(Id-K-C, ( member(rv(Id, X, K, _, B, _), Items), K \== u, K \== state,
                      ddc_compile:sweep_key_clause(Id, X, K, B, Info, C) ), SwKs),
    reference_distinct(SwKs, Distinct),
    findall(Id, member(Id-_-_, Distinct), Ids),
    findall(Id, M:'$sweep'(rv, _, _, Id), GotIds),
    assertion(GotIds == Ids).

%   The definition of distinct sweep keys: drop every later variant.
reference_distinct([], []).
reference_distinct([Id-K-C|T], [Id-K-C|Kept]) :-
    exclude(same_key(K, C), T, T1),
    reference_distinct(T1, Kept).

same_key(K, ('$sweep_key'(_, X, T, W) :- B), _-K2-('$sweep_key'(_, X2, T2, W2) :- B2)) :-
    K2 == K,
    s(X, T, W, B) =@= s(X2, T2, W2, B2).

:- begin_tests(ddc_load_scale).

test(rivals_and_purity_of_every_kind_of_head) :-
    kinds_program(File),
    call_cleanup(check_program(File), delete_file(File)).

test(rivals_of_every_kind_of_head_by_name) :-
    kinds_program(File),
    call_cleanup(( ddc_load(File, M), ddc_programs:program_items(M, All),
                   findall(L-R, ( member(rv(Id, _, _, _, _, L), All), memberchk(rivals(Id, R), All) ),
                           Pairs) ),
                 delete_file(File)),
    %   u(a) unifies with the later u(X); u(X) with u(b); u(b) has none later
    assertion(subset([6-true, 7-true, 8-false], Pairs)),
    %   w(f(a, B)) does not unify with w(f(b, _)) nor w(g)
    assertion(memberchk(9-false, Pairs)),
    %   first_applicable fa/1 and persistent kept/1 are never checked
    assertion(memberchk(12-false, Pairs)),
    assertion(memberchk(14-false, Pairs)),
    %   p(X):t+1 overlaps the later p(a):2 (h:N, N >= 1); p(a):2 the later
    %   p(a):t+1; p(a):0 the later p(X):0; p(X):0 only h:0 clauses (none later)
    assertion(subset([15-true, 16-true, 17-true, 18-false], Pairs)),
    %   h:t clauses are rivals of h:t clauses only
    assertion(subset([21-true, 22-false], Pairs)),
    %   r(X):1 overlaps the later r(a):1, not r(a):-1
    assertion(subset([23-true, 24-false, 25-false], Pairs)).

test(shipped_programs_compile_to_the_definitions, [forall(shipped_program(File))]) :-
    check_program(File).

%   A generated program of N random variable clauses (N/2 variables with
%   two clauses each, the second the first one's rival), N transitions of
%   as many variables, and N derived atoms in one chain ending at a random
%   variable: the fixpoint over the chain took one pass per link, the
%   rivals and the sweep keys one comparison per pair.
scale_program(N, File) :-
    tmp_file_stream(text, File, S),
    H is N // 2,
    forall(between(1, N, I),
           ( J is I mod H,
             format(S, "x(~d, A) ~~ gaussian(A, 1.0) := obj(~d, A).~n", [J, I]),
             format(S, "pos(o~d):t+1 ~~ gaussian(P, 0.1) := pos(o~d):t ~~= P.~n", [I, I]),
             I1 is I + 1,
             format(S, "d~d := d~d.~n", [I, I1]) )),
    N1 is N + 1,
    format(S, "d~d := x(1, 0.5) ~~= _.~n", [N1]),
    close(S).

load_inferences(N, Inferences) :-
    scale_program(N, File),
    call_cleanup(( statistics(inferences, I0),
                   ddc_load(File, _),
                   statistics(inferences, I1) ),
                 delete_file(File)),
    Inferences is I1 - I0.

test(loading_work_grows_linearly) :-
    load_inferences(500, Small),
    load_inferences(2000, Large),
    Ratio is Large / Small,
    %   4 times the clauses: about 4 times the work (it was about 16)
    assertion(Ratio < 6).

:- end_tests(ddc_load_scale).
