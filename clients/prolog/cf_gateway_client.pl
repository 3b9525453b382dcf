% A Common Framework agent in SWI-Prolog, over the TCP gateway.
%
%   swipl cf_gateway_client.pl HOST PORT NAME [TOKEN]
%
% It says hello, registers as a PlayerDecision, looks up a Kick provider,
% runs a fipa-request with it, then serves one fipa-request from any agent
% (ROS or TCP) and says bye. The S-expression reader/writer below is the part
% to copy into your agent. The protocol is in docs/gateway-protocol.md.
%
% Terms: a list is a Prolog list, "text" is a string, a number is a number,
% :key is kw(key), any other word is an atom.

:- use_module(library(socket)).
:- use_module(library(dcg/basics)).
:- initialization(main, main).

% ---- S-expressions -----------------------------------------------------------

sexp_codes(Term, Codes) :- phrase((blanks, sexp(Term), blanks), Codes).

sexp(List) --> "(", !, blanks, items(List), ")".
sexp(String) --> "\"", !, chars(Cs), "\"", { string_codes(String, Cs) }.
sexp(Term) --> word(Cs), { Cs \== [], word_term(Cs, Term) }.

items([T|Ts]) --> sexp(T), !, blanks, items(Ts).
items([]) --> [].

chars([C|Cs]) --> "\\", [E], !, { escape(E, C) }, chars(Cs).
chars([C|Cs]) --> [C], { C \== 0'" }, !, chars(Cs).
chars([]) --> [].

escape(0'n, 0'\n) :- !.
escape(0't, 0'\t) :- !.
escape(0'r, 0'\r) :- !.
escape(C, C).

word([C|Cs]) --> [C], { \+ code_type(C, space), \+ memberchk(C, `()"`) }, !, word(Cs).
word([]) --> [].

word_term([0':|Cs], kw(A)) :- !, atom_codes(A, Cs).
word_term(Cs, N) :- catch(number_codes(N, Cs), _, fail), !.
word_term(Cs, A) :- atom_codes(A, Cs).

write_sexp(Out, List) :- is_list(List), !,
    write(Out, '('), write_items(Out, List), write(Out, ')').
write_sexp(Out, kw(K)) :- !, format(Out, ':~w', [K]).
write_sexp(Out, S) :- string(S), !,
    split_string(S, "", "", [_]),
    string_codes(S, Cs), write(Out, '"'), forall(member(C, Cs), write_char(Out, C)), write(Out, '"').
write_sexp(Out, X) :- write(Out, X).

write_items(_, []).
write_items(Out, [X]) :- !, write_sexp(Out, X).
write_items(Out, [X|Xs]) :- write_sexp(Out, X), write(Out, ' '), write_items(Out, Xs).

write_char(Out, 0'") :- !, write(Out, '\\"').
write_char(Out, 0'\\) :- !, write(Out, '\\\\').
write_char(Out, 0'\n) :- !, write(Out, '\\n').
write_char(Out, C) :- put_char(Out, C).

% param(+Sexp, +Key, -Value): the value after :Key in (head :key value ...).
param([_|Items], Key, Value) :- append(_, [kw(Key), Value|_], Items), !.

text(S, S) :- string(S), !.
text(A, S) :- atom_string(A, S).

% ---- the connection ----------------------------------------------------------

send_line(Out, Term) :- write_sexp(Out, Term), nl(Out), flush_output(Out).

read_sexp(In, Term) :-
    read_line_to_codes(In, Codes),
    ( Codes == end_of_file -> throw(gateway_closed) ; sexp_codes(Term, Codes) ).

% connect(+Host, +Port, -Conn, -Stream): a UTF-8 connection to the gateway, with an empty inbox.
connect(Host, Port, conn(In, Out), Stream) :-
    nb_setval(inbox, []),
    tcp_connect(Host:Port, Stream, []),
    stream_pair(Stream, In, Out),
    set_stream(In, encoding(utf8)), set_stream(Out, encoding(utf8)).

% command(+Conn, +Term, +Expect, -Answer): send, wait for the form named Expect.
command(conn(In, Out), Term, Expect, Answer) :-
    send_line(Out, Term),
    wait_for(In, Expect, Answer).

wait_for(In, Expect, Answer) :-
    read_sexp(In, Line),
    Line = [Head|_],
    raise_if_refused(Line),
    (   Head == Expect -> Answer = Line
    ;   param(Line, sender, _) -> nb_getval(inbox, Box), append(Box, [Line], Box1), nb_setval(inbox, Box1),
        wait_for(In, Expect, Answer)
    ;   wait_for(In, Expect, Answer)
    ).

% receive(+Conn, -Msg): the next ACL message addressed to us.
receive(conn(_, _), Msg) :-
    nb_getval(inbox, [Msg|Rest]), !, nb_setval(inbox, Rest).
receive(conn(In, Out), Msg) :-
    read_sexp(In, Line),
    (   param(Line, sender, _) -> Msg = Line
    ;   % the gateway's own failure may be about a message we sent (an unknown receiver)
        raise_if_refused(Line), receive(conn(In, Out), Msg)
    ).

% raise_if_refused(+Line): throws gateway_error(Head, Why) when Line is the gateway's own
% failure, not-understood or error (it has no :sender); else succeeds.
raise_if_refused(Line) :-
    Line = [Head|_],
    (   memberchk(Head, [failure, 'not-understood', error]), \+ param(Line, sender, _)
    ->  ( param(Line, reason, Why) -> true ; Why = "" ), throw(gateway_error(Head, Why))
    ;   true
    ).

% request(+Conn, +Name, +Receiver, +Content, -Answer): request/6 with a 30 s timeout.
request(Conn, Name, Receiver, Content, Answer) :-
    request(Conn, Name, Receiver, Content, 30, Answer).

% request(+Conn, +Name, +Receiver, +Content, +Timeout, -Answer): fipa-request to its final
% answer, with :reply-by Timeout seconds from now; throws no_answer(Receiver, Timeout) when
% none came by then, and gateway_error(failure, Why) when the gateway refuses the message.
request(Conn, Name, Receiver, Content, Timeout, Answer) :-
    Conn = conn(In, Out),
    ( nb_current(conversations, N0) -> true ; N0 = 0 ), N is N0 + 1, nb_setval(conversations, N),
    format(atom(Cid), '~w-c~w', [Name, N]), format(atom(Rw), '~w-r1', [Cid]),
    get_time(Now), Deadline is Now + Timeout,
    fipa_time(Deadline, ReplyBy),
    send_line(Out, [request, kw(receiver), [set, ['agent-identifier', kw(name), Receiver]],
                    kw(content), Content, kw(language), 'cf-lang', kw(ontology), 'robocup-soccer',
                    kw(protocol), 'fipa-request', kw('conversation-id'), Cid, kw('reply-with'), Rw,
                    kw('reply-by'), ReplyBy]),
    nb_setval(held, []),
    catch(await_answer(Conn, Cid, Deadline, Answer), Error, true),
    set_stream(In, timeout(infinite)),
    % Messages of other conversations that came meanwhile go back to the inbox, in order.
    nb_getval(held, Held), nb_getval(inbox, Box), append(Held, Box, Box1), nb_setval(inbox, Box1),
    (   var(Error) -> true
    ;   Error = error(timeout_error(read, _), _) -> throw(no_answer(Receiver, Timeout))
    ;   throw(Error)
    ).

% fipa_time(+Stamp, -Atom): a FIPA date-time in UTC, to the millisecond: 20261125T101010123Z.
fipa_time(Stamp, Atom) :-
    stamp_date_time(Stamp, Date, 'UTC'),
    format_time(atom(Atom), '%Y%m%dT%H%M%S%3fZ', Date).

await_answer(Conn, Cid, Deadline, Answer) :-
    Conn = conn(In, _),
    get_time(Now), Left is max(0.001, Deadline - Now),
    set_stream(In, timeout(Left)),
    receive(Conn, Msg),
    (   param(Msg, 'conversation-id', C), text(C, Cs), text(Cid, Cs)
    ->  ( Msg = [agree|_] -> await_answer(Conn, Cid, Deadline, Answer) ; Answer = Msg )
    ;   nb_getval(held, H), append(H, [Msg], H1), nb_setval(held, H1),
        await_answer(Conn, Cid, Deadline, Answer)
    ).

reply(conn(_, Out), Request, Performative, Content) :-
    param(Request, sender, Sender), param(Sender, name, From),
    param(Request, 'conversation-id', Cid),
    ( param(Request, 'reply-with', Rw) -> InReplyTo = [kw('in-reply-to'), Rw] ; InReplyTo = [] ),
    ( Content == none -> Body = [] ; Body = [kw(content), Content] ),
    append([[Performative, kw(receiver), [set, ['agent-identifier', kw(name), From]]], Body,
            [kw(protocol), 'fipa-request', kw('conversation-id'), Cid], InReplyTo], Msg),
    send_line(Out, Msg).

% ---- the example agent -------------------------------------------------------

main :-
    current_prolog_flag(argv, [Host, PortA, NameA|Rest]),
    atom_number(PortA, Port), atom_string(NameA, Name),
    connect(Host, Port, Conn, Stream),
    ( Rest = [Token|_] -> atom_string(Token, T), Hello = [hello, kw(name), NameA, kw(token), T]
    ; Hello = [hello, kw(name), NameA] ),
    command(Conn, Hello, welcome, _),
    format("CONNECTED ~w~n", [Name]),
    command(Conn, [register, kw('service-class'), 'PlayerDecision', kw(team), "blue", kw(player), 10,
                   kw(lease), 2.0], registered, _),
    format("REGISTERED~n"),
    command(Conn, [lookup, kw('service-class'), 'Kick'], providers, [providers|Providers]),
    findall(P, (member(Pr, Providers), param(Pr, name, N), text(N, P)), Names),
    format("PROVIDERS ~w~n", [Names]),
    Names = [First|_], atom_string(FirstA, First),
    request(Conn, Name, FirstA, "(exec Player kick :playerNumber 10 :whichTeam our :power 55 :direction 0)", Answer),
    Answer = [Perf|_], param(Answer, content, Result),
    format("ANSWER ~w ~w~n", [Perf, Result]),
    format("SERVING~n"), flush_output,
    receive(Conn, Request),
    reply(Conn, Request, agree, none),
    reply(Conn, Request, inform, "(done-by-prolog)"),
    param(Request, sender, S), param(S, name, SenderName),
    format("SERVED ~w~n", [SenderName]),
    command(Conn, [bye], bye, _),
    format("BYE~n"),
    close(Stream).
