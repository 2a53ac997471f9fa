/*  ddc_source.pl -- the one reader of DC files: programs, learning data, declarative bias.

    Part of the DDC engine (ddc.pl is the module users load).  Opens a file, reads its terms
    with their variable names and lines, follows `:- include(File).`, applies `:- op/3`, and
    reports what keeps a file from being read (no such file, a syntax error, brackets nested
    too deep, a file that includes itself, a bad operator) as an ISO error term naming the
    file and line.  What a term means is its client's business: the engine's program loading
    (ddc_read.pl) and the learner's data (learn/ddc_learn_data.pl).
*/

:- module(ddc_source,
          [ source_file/3,              % +Spec, +Options, -File
            source_terms/3,             % +File, +Options, -Terms
            source_error/1              % +Error
          ]).

:- use_module(library(error)).
:- use_module(library(lists)).
:- use_module(library(modules)).
:- use_module(library(option)).
:- use_module(ddc_nesting, [file_too_deep/3]).

/** <module> The one reader of DC files

Every file the DDC engine or its learner reads (a program, learning data, a declarative bias,
a learned program read back) is read here, into a list of

    src(Term, VariableNames, File, Line)

one per clause or directive in file order: Term as read, VariableNames its `Name = Var` list,
File the absolute name of the file it stands in (an included file's own name) and Line its
first line there.

  - `:- include(Spec).` is replaced by the terms of the file Spec names, found relative to
    the including file as Prolog's include/1 finds it (a Prolog file first, then any file),
    read as if its text stood there: with the operators declared so far.
  - `:- op(P, Type, Names).` takes effect at once for the rest of the file and the files it
    includes, and for nothing else: the file is read in a temporary module whose base is the
    client's module (`module(M)`), so no file changes how another file or a query is read.
    The directive stays among the terms (a client may ignore it).

Errors are ISO error terms whose context is `context(ddc_source:PI, File:Line)`:

  - existence_error(source_sink, Spec): no such file (File:Line is the include directive's;
    the context's second argument is unbound for a file named by the caller);
  - syntax_error(Message): a term that does not parse; syntax_error(too_deep(Max)) for
    brackets nested deeper than Max (the reader would crash, ddc_nesting.pl);
  - permission_error(include, source_sink, File): a file that includes itself;
  - the error of op/3 (domain_error/2, permission_error/3, ...) for a bad `:- op/3`.

print_message/2 renders them as `File:Line: cause`, as the engine's and the learner's own
errors (`File:Line: syntax error: operator expected`, `File: no such file`).
*/

%!  source_file(+Spec, +Options:list, -File:atom) is det.
%
%   File is the absolute name of the readable file Spec names.  Options:
%   prefer(prolog) (default) tries a Prolog file (Spec.pl) before the name as it is, as
%   consult/1 does; prefer(exact) the name as it is before Spec.pl.
%
%   @error existence_error(source_sink, Spec) if there is none.
source_file(Spec, Options, File) :-
    option(prefer(Prefer), Options, prolog),
    must_be(oneof([prolog, exact]), Prefer),
    (   resolved(Prefer, Spec, [], File0)
    ->  File = File0
    ;   throw(error(existence_error(source_sink, Spec),
                    context(ddc_source:source_file/3, _)))
    ).

%   resolved(+Prefer, +Spec, +Relative, -File): the file Spec names (Relative: [] or
%   [relative_to(F)]), in the order Prefer says; fails if there is none.
resolved(prolog, Spec, Rel, File) :-
    (   absolute_file_name(Spec, File, [file_type(prolog), access(read), file_errors(fail)|Rel])
    ->  true
    ;   absolute_file_name(Spec, File, [access(read), file_errors(fail)|Rel])
    ).
resolved(exact, Spec, Rel, File) :-
    (   absolute_file_name(Spec, File, [access(read), file_errors(fail)|Rel])
    ->  true
    ;   absolute_file_name(Spec, File, [extensions([pl]), access(read), file_errors(fail)|Rel])
    ).

%!  source_terms(+File:atom, +Options:list, -Terms:list) is det.
%
%   Terms is a list of src(Term, VariableNames, File1, Line) for the clauses and directives
%   of File (an absolute file name, as source_file/3 gives it) and of the files it includes
%   (File1 the file a term stands in).  Options: module(M) (default user): the module whose
%   operators the text is read with; variable_names(false) leaves VariableNames [] (a little
%   faster, for a client that does not need them); check_nesting(false) skips the scan of
%   the bracket depth before each file is read (ddc_nesting.pl: 0.76 s for the 1.5 MB of the
%   Financial data, more than reading it; a text nested 15,000 brackets deep then crashes
%   the reader inside janus).
%
%   @error existence_error(source_sink, Spec), syntax_error(Message),
%   permission_error(include, source_sink, File) or op/3's error, each with
%   context(ddc_source:source_terms/3, File:Line).
source_terms(File, Options, Terms) :-
    must_be(atom, File),
    option(module(M), Options, user),
    must_be(atom, M),
    option(variable_names(Names), Options, true),
    must_be(boolean, Names),
    option(check_nesting(Check), Options, true),
    must_be(boolean, Check),
    in_temporary_module(Reader,
                        set_module(Reader:base(M)),
                        read_file(File, reader(Reader, Names, Check), [], Terms, [])).

%   read_file(+File, +Reader, +Stack, -Terms, ?Tail): the terms of File (and of the files it
%   includes) as a difference list; Reader is reader(Module, VariableNames, CheckNesting);
%   Stack the files being read, innermost first.
read_file(File, Reader, Stack, Terms, Tail) :-
    (   arg(3, Reader, true),
        file_too_deep(File, Max, Line)
    ->  reader_error(syntax_error(too_deep(Max)), File:Line)
    ;   true
    ),
    setup_call_cleanup(
        open(File, read, S),
        read_terms(S, File, Reader, [File|Stack], Terms, Tail),
        close(S)).

read_terms(S, File, Reader, Stack, Terms, Tail) :-
    Reader = reader(M, Names, _),
    (   Names == true
    ->  Opts = [module(M), term_position(P), variable_names(Vs), syntax_errors(error)]
    ;   Opts = [module(M), term_position(P), syntax_errors(error)], Vs = []
    ),
    catch(read_term(S, T, Opts), E, syntax_error(E, File)),
    (   T == end_of_file
    ->  Terms = Tail
    ;   stream_position_data(line_count, P, Line),
        (   include_directive(T, Spec)
        ->  included_file(Spec, File, Stack, File:Line, Inc),
            read_file(Inc, Reader, Stack, Terms, Rest)
        ;   op_directive(T, M, File:Line),
            Terms = [src(T, Vs, File, Line)|Rest]
        ),
        read_terms(S, File, Reader, Stack, Rest, Tail)
    ).

include_directive(T, Spec) :-
    nonvar(T), T = (:- D), nonvar(D), D = include(Spec).

%   included_file(+Spec, +File, +Stack, +Where, -Included): the file that
%   `:- include(Spec)` in File names, relative to File's folder.
included_file(Spec, File, Stack, Where, Inc) :-
    (   ground(Spec),
        resolved(prolog, Spec, [relative_to(File)], Inc0)
    ->  (   memberchk(Inc0, Stack)
        ->  reader_error(permission_error(include, source_sink, Inc0), Where)
        ;   Inc = Inc0
        )
    ;   reader_error(existence_error(source_sink, Spec), Where)
    ).

%   op_directive(+Term, +Reader, +Where): an op/3 directive takes effect in the reading
%   module at once; its error (a bad priority or type, redefining `,` or `|`) is the file's
%   at Where.
op_directive(T, Reader, Where) :-
    nonvar(T), T = (:- D), nonvar(D), D = op(P, Type, Names), !,
    catch(op(P, Type, Reader:Names), error(Formal, _), reader_error(Formal, Where)).
op_directive(_, _, _).

syntax_error(error(syntax_error(Msg), Ctx), File) :- !,
    (   Ctx = stream(_, Line, _, _) -> true
    ;   Ctx = file(_, Line, _, _) -> true
    ;   Line = 0
    ),
    reader_error(syntax_error(Msg), File:Line).
syntax_error(E, _) :-
    throw(E).

reader_error(Formal, Where) :-
    throw(error(Formal, context(ddc_source:source_terms/3, Where))).

%!  source_error(+Error) is semidet.
%
%   Error is one of this reader's (a file that cannot be read).
source_error(E) :-
    nonvar(E), E = error(_, Ctx), nonvar(Ctx), Ctx = context(PI, _),
    nonvar(PI), PI = ddc_source:_.

                 /*******************************
                 *            MESSAGES          *
                 *******************************/

:- multifile prolog:message//1.

prolog:message(error(Formal, Ctx)) -->
    { nonvar(Formal), source_error(error(Formal, Ctx)), Ctx = context(_, Where) },
    source_message(Formal, Where).

source_message(existence_error(source_sink, Spec), Where) -->
    { var(Where) }, !,
    [ '~w: no such file'-[Spec] ].
source_message(Formal, File:Line) -->
    { integer(Line), Line > 0 }, !,
    [ '~w:~w: '-[File, Line] ],
    source_cause(Formal).
source_message(Formal, File:_) -->
    [ '~w: '-[File] ],
    source_cause(Formal).

source_cause(existence_error(source_sink, Spec)) --> !, [ 'no such file: ~w'-[Spec] ].
source_cause(syntax_error(too_deep(Max))) --> !,
    [ 'brackets nest deeper than ~D, the most the reader takes'-[Max] ].
source_cause(syntax_error(Msg)) --> !, [ 'syntax error: ~w'-[Msg] ].
source_cause(permission_error(include, source_sink, File)) --> !,
    [ 'the file ~w includes itself'-[File] ].
source_cause(Formal) -->
    '$messages':translate_message(error(Formal, _)).
