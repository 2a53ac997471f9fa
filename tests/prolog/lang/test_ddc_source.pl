/*  plunit tests of the one reader of DC files (prolog/ddc/lang/ddc_source.pl): terms with
    their variable names, files and lines; includes found relative to the including file;
    operators of a file for the rest of that file only; what keeps a file from being read as
    an ISO error term naming the file and line, printed as `File:Line: cause`.
*/
:- use_module('../../../prolog/ddc/lang/ddc_source').
:- use_module('../../../prolog/ddc/lang/ddc_ops').
:- use_module(library(plunit)).
:- use_module('../temp_files').
:- use_module(library(lists)).

%   read_error(+Goal, -Formal, -Where): Goal throws the reader's error Formal at Where.
read_error(G, Formal, Where) :-
    catch((G, fail), error(Formal, context(ddc_source:_, Where)), true).

message(G, Text) :-
    catch((G, fail), E, true),
    '$messages':translate_message(E, Lines, []),
    with_output_to(string(Text0), print_message_lines(current_output, '', Lines)),
    split_string(Text0, "", "\n", [Text]).

:- begin_tests(ddc_source).

test(terms_with_names_files_and_lines) :-
    files([ 'main.pl'-['a ~ val(1).', '', 'b(X) := a ~= X.'] ], D),
    path(D, 'main.pl', F),
    source_terms(F, [module(ddc_ops)], Terms),
    Terms = [src(a ~ val(1), [], F, 1), src((b(X) := a ~= Y), ['X'=X0], F, 3)],
    X == X0, X == Y,
    source_terms(F, [module(ddc_ops), variable_names(false)], [_, src(_, [], F, 3)]).

test(included_terms_name_their_file) :-
    files([ 'main.pl'-['a.', ':- include(\'lib/base\').', 'd.'],
            'lib/base.pl'-['b.', ':- include(more).'],
            'lib/more.pl'-['', 'c.'] ], D),
    path(D, 'main.pl', F), path(D, 'lib/base.pl', B), path(D, 'lib/more.pl', M),
    source_terms(F, [], Terms),
    Terms == [src(a, [], F, 1), src(b, [], B, 1), src(c, [], M, 2), src(d, [], F, 3)].

test(an_operator_applies_to_the_rest_of_its_file_only) :-
    files([ 'own.pl'-[':- op(700, xfx, likes).', 'mary likes wine.'],
            'other.pl'-['p.', 'mary likes wine.'] ], D),
    path(D, 'own.pl', Own), path(D, 'other.pl', Other),
    source_terms(Own, [], [src((:- op(700, xfx, likes)), _, Own, 1), src(likes(mary, wine), _, Own, 2)]),
    read_error(source_terms(Other, [], _), syntax_error(_), Other:2).

test(no_such_file) :-
    read_error(source_file(nowhere_such_file, [], _), existence_error(source_sink, nowhere_such_file), W),
    var(W),
    message(source_file(nowhere_such_file, [], _), Text),
    Text == "nowhere_such_file: no such file".

test(no_such_included_file) :-
    files([ 'main.pl'-['a.', ':- include(nowhere).'] ], D),
    path(D, 'main.pl', F),
    read_error(source_terms(F, [], _), existence_error(source_sink, nowhere), F:2),
    message(source_terms(F, [], _), Text),
    format(string(Expected), "~w:2: no such file: nowhere", [F]),
    Text == Expected.

test(syntax_error_names_the_included_file) :-
    files([ 'main.pl'-['a.', ':- include(base).'],
            'base.pl'-['b.', 'c(.'] ], D),
    path(D, 'main.pl', F), path(D, 'base.pl', B),
    read_error(source_terms(F, [], _), syntax_error(_), B:2),
    message(source_terms(F, [], _), Text),
    format(string(Prefix), "~w:2: syntax error: ", [B]),
    sub_string(Text, 0, _, _, Prefix).

test(a_file_that_includes_itself) :-
    files([ 'main.pl'-[':- include(main).'] ], D),
    path(D, 'main.pl', F),
    read_error(source_terms(F, [], _), permission_error(include, source_sink, F), F:1),
    message(source_terms(F, [], _), Text),
    format(string(Expected), "~w:1: the file ~w includes itself", [F, F]),
    Text == Expected.

test(a_bad_operator) :-
    files([ 'main.pl'-['a.', ':- op(700, zfz, foo).'] ], D),
    path(D, 'main.pl', F),
    read_error(source_terms(F, [], _), domain_error(operator_specifier, zfz), F:2).

test(brackets_nested_too_deep) :-
    files([ 'main.pl'-['a.'] ], D),
    path(D, 'main.pl', F),
    setup_call_cleanup(open(F, append, S),
                       ( format(S, "b :- ~n", []),
                         forall(between(1, 10001, _), put_char(S, '(')), nl(S) ),
                       close(S)),
    read_error(source_terms(F, [], _), syntax_error(too_deep(10000)), F:3),
    message(source_terms(F, [], _), Text),
    once(sub_string(Text, _, _, _, "brackets nest deeper than 10,000")).

:- end_tests(ddc_source).
