/** <module> The DDC system's errors: at run time, and as messages

Part of the DDC system (ddc.pl is the module users load).  Every error
of a program is error(ddc(Cause, Where), _) (a file that cannot be read
at all, the reader's ISO error, ddc_source.pl); this module names the
program's clause in an error raised while it runs, and renders the
errors as messages (File:Line: cause).
*/

:- module(ddc_errors,
          [ engine_error/1              % +Error
          ]).

:- use_module(ddc_programs, [program_file_/2]).
:- use_module(ddc_source, [source_error/1]).

:- multifile prolog:message//1.

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
    (   clause(Head, ddc_errors:program_error(E0, E, Frame, Catcher))
    ->  true
    ;   asserta((Head :- ddc_errors:program_error(E0, E, Frame, Catcher)))
    ).

:- initialization(install_exception_hook).

%!  program_error(+Error, -ProgramError, +Frame, +Catcher) is semidet.
program_error(E0, E, Frame, Catcher) :-
    \+ engine_error(E0),
    \+ caught_by_program(Catcher),
    program_frame_depth(Depth),
    program_frame(Frame, Catcher, Depth, M, Ref),
    M:'$clause_line'(Ref, Line),
    program_file_(M, File), !,
    E = error(ddc(prolog_error(E0), File:Line), _).

%!  engine_error(+Error) is semidet.
%
%   Error is one of the engine's own (or an abort, a time limit): left as
%   it is, not turned into the error of a program's clause.
engine_error(E) :- var(E), !.
engine_error(error(ddc(_, _), _)).
engine_error(error(ddc_distribution(_, _), _)).
engine_error(E) :- source_error(E).     % a file that cannot be read (ddc_source.pl)
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

%   program_frame_depth(-Depth): how many frames up from where an error
%   was raised a clause of a program is looked for.
program_frame_depth(200).

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

where(_:(File:Line)) --> { integer(Line) }, !, where(File:Line).   % in an included file
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
cause(bad_directive(D)) --> !, [ 'unknown directive ~p'-[D] ].
cause(bad_head(H)) --> !,
    [ 'not a clause head: ~p (a random variable is defined by ~~ or :=, e.g. h:t+1 := true)'-[H] ].
cause(fresh_arithmetic) --> !,
    [ 'arithmetic (is/2 or a comparison) reads a variable that nothing before it binds' ].
cause(unbound_head) --> !, [ 'the clause head is a variable' ].
cause(unbound_body) --> !, [ 'the directive or clause body is a variable' ].
cause(query_never_holds(Q)) --> !, [ 'the query ~p never holds in a sample that counts'-[Q] ].
cause(batched_unsupported(What)) --> !,
    [ 'outside what the batched filter evaluates (use engine per_particle): ~p'-[What] ].
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

