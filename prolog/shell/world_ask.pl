/*  world_ask.pl -- a query on a world model, answered as JSON.

    Used with world.pl (which holds the world model's facts in module user):
    `anchoring shell --query` prints the answers of one query; `anchoring run --serve`
    keeps a swipl process running serve/0, to which it hands the world model of the
    run's last whole frame and the queries that come in over its query server.
*/

:- module(anchoring_world_ask,
          [ ask_json/3,         % +QueryText, +Options, -Dict
            print_answers/2,    % +QueryText, +Options
            serve/0
          ]).

:- use_module(library(apply)).
:- use_module(library(error)).
:- use_module(library(lists)).
:- use_module(library(option)).
:- use_module(library(sandbox)).
:- use_module(library(solution_sequences)).
:- use_module(library(time)).
:- use_module(library(http/json)).
:- use_module(world).

:- dynamic user:world_frame/2.

/** <module> A query on a world model, answered as JSON

A query is Prolog text, read as the world-model shell (prolog/shell/world.pl) reads it at its
prompt: `hidden_under(Obj, Occ, P)`, `prob(occluded_by(ball_1, mug_1), P)`,
`anchor(A, S, C, Seen, T)`.  Its answer is a JSON object:

    {"answers": [{"Obj": "ball_1", "Occ": "mug_1", "P": 0.93}, ...], "truncated": false,
     "frame": 57, "time": 11.4}

one object per solution, with the query's named variables (those not starting with `_`);
numbers stay numbers, atoms and strings are strings, comma terms (X,Y,Z) and lists are
arrays, other terms their quoted text, an unbound variable `"_"`; frame and time are the
world model's (world_frame/2), when it says.  A query that raises,
does not parse, takes longer than its time limit or (with sandbox(true)) could do more than
read the world model and compute gives {"error": Message}.  A query runs in snapshot/1:
whatever it asserts or retracts is undone after it.
*/

%   The world model's facts are read-only data: safe for a sandboxed query.
:- multifile sandbox:safe_primitive/1, sandbox:safe_meta/2.
sandbox:safe_primitive(user:anchor(_, _, _, _, _)).
sandbox:safe_primitive(user:attribute(_, _, _)).
sandbox:safe_primitive(user:particle(_, _)).
sandbox:safe_primitive(user:particle_fact(_, _)).
sandbox:safe_primitive(user:identity(_, _, _)).
sandbox:safe_primitive(user:world_frame(_, _)).
%   prob/2 calls the tests of its goal (X > 0.1) in module user: they must be safe.
sandbox:safe_meta(anchoring_world:prob(G, _), Called) :-
    phrase(prob_tests(G), Called).

prob_tests(V) --> { var(V) }, !, [user:V].
prob_tests(identity(_, _)) --> !.
prob_tests((A, B)) --> !, prob_tests(A), prob_tests(B).
prob_tests(\+ A) --> !, prob_tests(A).
prob_tests(pos(_, _)) --> !.
prob_tests(occluded_by(_, _)) --> !.
prob_tests(G) --> [user:G].

%!  ask_json(+QueryText, +Options, -Dict:dict) is det.
%
%   The answers of the query in QueryText as a dict (see the module's documentation).
%   Options: max(N), the most answers given (1000; more make truncated true);
%   time_limit(Seconds) (10); sandbox(Bool): refuse a query that could do more than read
%   (library(sandbox); false).
ask_json(Text, Options, Dict) :-
    must_be(text, Text),
    option(max(Max), Options, 1000),
    option(time_limit(Limit), Options, 10),
    option(sandbox(Sandbox), Options, false),
    catch(answers(Text, Max, Limit, Sandbox, Answers, Truncated), E, true),
    (   var(E)
    ->  Dict0 = _{answers: Answers, truncated: Truncated}
    ;   error_text(E, Message),
        Dict0 = _{error: Message}
    ),
    (   user:world_frame(Frame, Time)
    ->  Dict = Dict0.put(_{frame: Frame, time: Time})
    ;   Dict = Dict0
    ).

answers(Text, Max, Limit, Sandbox, Answers, Truncated) :-
    term_string(Goal, Text, [variable_names(Bindings), module(user)]),
    (   Sandbox == true -> safe_goal(user:Goal) ; true ),
    exclude(hidden_name, Bindings, Named),
    Max1 is Max + 1,
    % in a snapshot: what the query asserts or retracts is gone after it (sandboxed queries
    % may change dynamic predicates), so every query sees the world model as it was loaded
    call_with_time_limit(Limit, snapshot(findall(Named, limit(Max1, user:Goal), Solutions0))),
    (   length(Solutions0, N), N > Max
    ->  length(Solutions, Max), append(Solutions, _, Solutions0), Truncated = true
    ;   Solutions = Solutions0, Truncated = false
    ),
    maplist(solution_dict, Solutions, Answers).

hidden_name(Name = _) :- sub_atom(Name, 0, 1, _, '_').

solution_dict(Named, Dict) :-
    maplist([Name = Value, Name - J]>>json_value(Value, J), Named, Pairs),
    dict_pairs(Dict, _, Pairs).

%   json_value(+Term, -Json): numbers as they are (not finite: their text), atoms and
%   strings as strings, comma terms and lists as arrays, other terms as their text.
json_value(V, "_") :- var(V), !.
json_value(N, J) :- number(N), !,
    (   float(N), \+ ( N =:= N, abs(N) =< 1.0e308 ) -> format(string(J), "~w", [N]) ; J = N ).
json_value(A, S) :- atom(A), !, atom_string(A, S).
json_value(S, S) :- string(S), !.
json_value(L, J) :- is_list(L), !, maplist(json_value, L, J).
json_value((A, B), [JA|JB]) :- !, json_value(A, JA), comma_values(B, JB).
json_value(T, S) :- format(string(S), "~q", [T]).

comma_values((A, B), [JA|JB]) :- !, json_value(A, JA), comma_values(B, JB).
comma_values(A, [JA]) :- json_value(A, JA).

%   error_text(+Error, -Text): the message SWI-Prolog prints for Error, on one line.
error_text(time_limit_exceeded, "the query took longer than its time limit") :- !.
error_text(E, S) :-
    catch(( '$messages':translate_message(E, Lines, []),
            with_output_to(string(S0), print_message_lines(current_output, '', Lines)),
            split_string(S0, "", "\n ", [S1]),
            split_string(S1, "\n", " ", Parts),
            atomic_list_concat(Parts, ' ', A),
            atom_string(A, S)
          ), _, fail), !.
error_text(E, S) :- format(string(S), "~q", [E]).

%!  print_answers(+QueryText, +Options) is det.
%
%   ask_json/3, written as one line of JSON on standard output.
print_answers(Text, Options) :-
    ask_json(Text, Options, Dict),
    json_write_dict(current_output, Dict, [width(0)]),
    nl.

%!  serve is det.
%
%   Commands read as terms from standard input, one JSON line written for each on
%   standard output, until end of file:
%
%     - load(File): the world file File replaces the world model (load_world/1);
%       answers {"loaded": File};
%     - ask(QueryText, Max, Seconds): ask_json/3 with max(Max), time_limit(Seconds)
%       and sandbox(true).
serve :-
    set_stream(user_output, encoding(utf8)),
    repeat,
    catch(read_term(user_input, Command, []), E, (error_text(E, M), Command = bad(M))),
    (   Command == end_of_file
    ->  !
    ;   command(Command, Dict),
        json_write_dict(user_output, Dict, [width(0)]),
        nl(user_output),
        flush_output(user_output),
        fail
    ).

command(load(File), Dict) :- !,
    catch(( load_world(File), Dict = _{loaded: File} ), E,
          ( error_text(E, M), Dict = _{error: M} )).
command(ask(Text, Max, Seconds), Dict) :- !,
    ask_json(Text, [max(Max), time_limit(Seconds), sandbox(true)], Dict).
command(bad(Message), _{error: Message}) :- !.
command(Other, _{error: Message}) :-
    format(string(Message), "unknown command ~q", [Other]).
