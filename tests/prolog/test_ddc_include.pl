/*  plunit tests of `:- include(File).` in DC programs (prolog/ddc/lang/ddc_source.pl): the included
    file's clauses are the program's, it is found relative to the including file, and every
    error about one of its clauses names the included file and its line.
*/
:- use_module('../../prolog/ddc').
:- use_module(library(plunit)).
:- use_module(temp_files).
:- use_module(library(lists)).

%   error_where(+Goal, -Cause, -File, -Line): Goal throws a ddc error about File:Line (in an
%   included file, the error names the included file), or the reader's (ddc_source.pl: a
%   file that cannot be read, Cause its ISO formal term).
error_where(G, Cause, File, Line) :-
    catch((G, fail), error(Formal, Ctx), true),
    (   Formal = ddc(Cause, Where) -> true
    ;   Ctx = context(ddc_source:_, Where) -> Cause = Formal
    ),
    (   Where = _:(File:Line), integer(Line) -> true
    ;   Where = File:Line
    ).

%   message(+Goal, -Text): the message Goal's error prints.
message(G, Text) :-
    catch((G, fail), E, true),
    message_to_codes(E, Text).

message_to_codes(E, Text) :-
    '$messages':translate_message(E, Lines, []),
    with_output_to(string(Text), print_message_lines(current_output, '', Lines)).

:- begin_tests(ddc_include).

test(included_clauses_are_the_programs) :-
    files([ 'main.pl'-[':- include(\'lib/base.pl\').', 'b ~ val(V) := a ~= A, V is A + 1.'],
            'lib/base.pl'-['% the base', 'a ~ val(1).'] ], D),
    path(D, 'main.pl', F),
    ddc_load(F, M),
    query(true, b ~= 2, P, [program(M), samples(5)]),
    P =:= 1.0.

test(found_relative_to_the_including_file) :-
    %   lib/base.pl includes its neighbour lib/more.pl by its bare name.
    files([ 'main.pl'-[':- include(\'lib/base\').', 'c := a ~= 1, b ~= 2.'],
            'lib/base.pl'-[':- include(more).', 'a ~ val(1).'],
            'lib/more.pl'-['b ~ val(2).'] ], D),
    path(D, 'main.pl', F),
    ddc_load(F, M),
    query(true, c, P, [program(M), samples(5)]),
    P =:= 1.0.

test(operators_of_the_included_file_apply_after_it) :-
    files([ 'main.pl'-[':- include(ops).', 'a ~ val(1) := 2 plus 3.'],
            'ops.pl'-[':- op(700, xfx, plus).', 'X plus Y :- X < Y.'] ], D),
    path(D, 'main.pl', F),
    ddc_load(F, M),
    query(true, a ~= 1, P, [program(M), samples(5)]),
    P =:= 1.0.

test(load_error_names_the_included_file_and_line) :-
    files([ 'main.pl'-['x ~ val(0).', ':- include(base).'],
            'base.pl'-['a ~ val(1).', '', 'b ~ nosuch(1, 2).'] ], D),
    path(D, 'main.pl', F), path(D, 'base.pl', B),
    error_where(ddc_load(F), distribution(_, unknown_distribution), B, 3),
    message(ddc_load(F), Text),
    format(atom(Prefix), "~w:3: ", [B]),
    sub_string(Text, 0, _, _, Prefix).

test(run_time_error_names_the_included_file_and_line) :-
    files([ 'main.pl'-[':- include(base).', 'a ~ val(1).'],
            'base.pl'-['', 'b ~ gaussian(0, V) := a ~= A, V is -A.'] ], D),
    path(D, 'main.pl', F), path(D, 'base.pl', B),
    ddc_load(F, M),
    error_where(query(true, b ~= _, _, [program(M), samples(5)]),
                distribution(_, negative_variance), B, 2).

test(syntax_error_names_the_included_file) :-
    files([ 'main.pl'-['a ~ val(1).', ':- include(base).'],
            'base.pl'-['b ~ val(2).', 'c ~ val(3) := b ~= 2', 'd ~ val(4).'] ], D),
    path(D, 'main.pl', F), path(D, 'base.pl', B),
    error_where(ddc_load(F), syntax_error(_), B, L),
    memberchk(L, [2, 3]).

test(lines_of_the_including_file_stay_its_own) :-
    files([ 'main.pl'-[':- include(base).', '', 'b ~ nosuch(1).'],
            'base.pl'-['a ~ val(1).'] ], D),
    path(D, 'main.pl', F),
    error_where(ddc_load(F), distribution(_, unknown_distribution), F, 3).

test(no_such_included_file) :-
    files([ 'main.pl'-['a ~ val(1).', ':- include(nowhere).'] ], D),
    path(D, 'main.pl', F),
    error_where(ddc_load(F), existence_error(source_sink, nowhere), F, 2).

test(a_file_that_includes_itself) :-
    files([ 'main.pl'-[':- include(base).'],
            'base.pl'-['a ~ val(1).', ':- include(main).'] ], D),
    path(D, 'main.pl', F), path(D, 'base.pl', B),
    error_where(ddc_load(F), permission_error(include, source_sink, F), B, 2).

:- end_tests(ddc_include).
