/*  ddc_learn_records.pl -- the structure learner's records with named
    fields (ddc_records.pl): a candidate literal, a node of a tree, the
    state of a walk along a path.
*/

:- module(ddc_learn_records,
          [ % The declarations below define and export, per record R and
            % field F: R_F/2 (read), set_R_F/2, nb_set_R_F/2, new_R/1 and
            % R_fields/1; calls are compiled inline to arg/3.
          ]).

:- use_module('../lang/ddc_records').

/** <module> Records of the structure learner

  - candidate(Mode, Kind, Goal, Inputs, Fresh, Value, Domain, Thresholds,
    Aggregate, Literal): an instance of a mode at a node (stored as
    '$ddcl_cand'(Id, Key, Candidate) in the data module).
      - Mode: the id of the mode ('$ddcl_mode'/6) it instantiates;
      - Kind: discrete, numeric, threshold, test, count, agg_numeric or
        agg_discrete (its branches: the table in ddc/learn.pl);
      - Goal: the literal in the internal form (an aggregate's: its
        condition and literal);
      - Inputs: [P-V]: the literal's variable V takes the node's variable
        at position P;
      - Fresh: [v(Type, V)]: the new variables a relational literal binds;
      - Value: the variable of the value it reads (none for a test);
      - Domain: the values of a discrete attribute or a mode aggregate;
      - Thresholds: the cut points of a threshold attribute;
      - Aggregate: none, count, mean, max, min, mode or antimode;
      - Literal: lit(Cond, Lit, Locals), an aggregate's condition, its
        literal and their own new variables [v(Type, V)], for the DC text.
  - node_info(Target, Vars, Used, Path): a node of a tree (stored as
    '$ddcl_node'(Id, NodeInfo, Rows)).
      - Target: target(Name, KeyArity, Spec) of the tree;
      - Vars: the node's variables v(Name, Type), the head's key
        arguments first;
      - Used: the candidates on the path from the root;
      - Path: the steps step(CandidateId, Branch) from the root.
  - path_state(Literals, Values, Names, Step, Regressors): a walk along a
    path of a tree while its clause is written.
      - Literals: the body literals so far, last first;
      - Values: the terms of the node's variables (VarTerms);
      - Names: the variable names Name=Var;
      - Step: the index of the next step (from 0);
      - Regressors: Step-Variable pairs, the value each step gives.
*/

:- record_type candidate(mode, kind, goal, inputs, fresh, value, domain, thresholds,
                         aggregate, literal).
:- record_type node_info(target, vars, used, path).
:- record_type path_state(literals, values, names, step, regressors).
