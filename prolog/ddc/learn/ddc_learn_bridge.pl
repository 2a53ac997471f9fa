/*  ddc_learn_bridge.pl -- the learner's predicates that take their options as a dict, for
    callers that hold data rather than Prolog terms (python/bridge/learning.py, through
    the adapter python/bridge/prolog.py).
*/

:- module(ddc_learn_bridge,
          [ learn_bridge_load/3,          % +Files, +Options:dict, -Data
            learn_bridge_forget/2,        % +Data, +Nodes
            learn_bridge_tree_text/3,     % +Data, +Leaves, -Texts
            learn_bridge_program_scores/5, % +Data, +File, +Targets, +Options:dict, -Scores
            learn_bridge_split_files/3,   % +Files, +Options:dict, -Stats
            learn_bridge_fold_files/4     % +Files, +Parts, +Options:dict, -Stats
          ]).

:- use_module(library(apply)).
:- use_module(library(error)).
:- use_module(library(lists)).
:- use_module('../learn.pl', [learn_load/3, learn_forget/2, learn_tree_text/3,
                              learn_program_scores/5]).
:- use_module(ddc_learn_split, [learn_split_files/3, learn_fold_files/3]).

/** <module> The learner's API for callers that pass data

Each predicate here is one of the learner's (library(ddc/learn),
ddc_learn_split.pl) whose options come as a dict, as a Python dict arrives
through janus, instead of a list of Name(Value) terms: the key of an entry
is the option's name, its value the option's value.  A key whose value is a
list and whose option is repeated (programs, below) gives one option per
item.  Errors are the learner's (error(ddc_learn(Cause, File:Line), _) for
bad data), raised, not caught.
*/

%!  learn_bridge_load(+Files:list, +Options:dict, -Data:atom) is det.
%
%   learn_load/3 with the options of the dict Options: samples, max_worlds,
%   targets (`true` or `false`), seed (optional), bias_files (a list) and
%   programs (a list of files: one program(File) option each).
learn_bridge_load(Files, Options, Data) :-
    must_be(dict, Options),
    dict_pairs(Options, _, Pairs),
    foldl(load_option, Pairs, OptionList, []),
    learn_load(Files, OptionList, Data).

load_option(programs-Ps, Os0, Os) :- !,
    must_be(list, Ps),
    foldl([P, [program(P)|T], T]>>true, Ps, Os0, Os).
load_option(targets-true, Os, Os) :- !.
load_option(Key-Value, [Option|Os], Os) :-
    Option =.. [Key, Value].

%!  learn_bridge_forget(+Data, +Nodes:list(integer)) is det.
%
%   learn_forget/2 of each of Nodes.
learn_bridge_forget(Data, Nodes) :-
    must_be(list(integer), Nodes),
    maplist(learn_forget(Data), Nodes).

%!  learn_bridge_tree_text(+Data, +Leaves:list, -Texts:list(string)) is det.
%
%   Texts is [Text] for learn_tree_text/3's Text, [] when it fails (the
%   leaves' distributions are not of one family).
learn_bridge_tree_text(Data, Leaves, Texts) :-
    (   learn_tree_text(Data, Leaves, Text) -> Texts = [Text] ; Texts = [] ).

%!  learn_bridge_program_scores(+Data, +File, +Targets:list, +Options:dict, -Scores) is det.
%
%   learn_program_scores/5 with the options of the dict Options (examples:
%   `true` or `false`).
learn_bridge_program_scores(Data, File, Targets, Options, Scores) :-
    options_list(Options, OptionList),
    learn_program_scores(Data, File, Targets, OptionList, Scores).

%!  learn_bridge_split_files(+Files:list, +Options:dict, -Stats:dict) is det.
%
%   learn_split_files/3 with the options of the dict Options (train, test,
%   fraction, seed, unit).
learn_bridge_split_files(Files, Options, Stats) :-
    options_list(Options, OptionList),
    learn_split_files(Files, OptionList, Stats).

%!  learn_bridge_fold_files(+Files:list, +Parts:list, +Options:dict, -Stats:list(dict)) is det.
%
%   learn_fold_files/3 with the folds' files Parts, a list of [Train, Test]
%   lists, and the options of the dict Options (seed, unit).
learn_bridge_fold_files(Files, Parts, Options, Stats) :-
    must_be(list(list), Parts),
    maplist([[Tr, Te], Tr-Te]>>true, Parts, Pairs),
    options_list(Options, OptionList),
    learn_fold_files(Files, [parts(Pairs)|OptionList], Stats).

options_list(Options, List) :-
    must_be(dict, Options),
    dict_pairs(Options, _, Pairs),
    maplist([K-V, O]>>(O =.. [K, V]), Pairs, List).
