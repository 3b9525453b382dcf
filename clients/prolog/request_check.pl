% Checks how request/6 of cf_gateway_client.pl ends when no answer comes, so that a test can see
% it from outside:
%
%   swipl -g "consult('clients/prolog/request_check.pl')" -g request_check -t halt \
%         clients/prolog/cf_gateway_client.pl HOST PORT NAME MUTE
%
% First a request to a name nobody registered: the gateway's failure must end it ("UNKNOWN <why>").
% Then a request to MUTE, an agent that takes messages and never answers, with a 1 s timeout:
% it must end in time ("TIMEOUT <why>"). A message of another conversation that came meanwhile
% must still be there to receive ("KEPT <content>"). Halts with 0 when all went as it should, else 1.

request_check :-
    current_prolog_flag(argv, [Host, PortA, NameA, Mute|_]),
    atom_number(PortA, Port),
    connect(Host, Port, Conn, Stream),
    command(Conn, [hello, kw(name), NameA], welcome, _),
    command(Conn, [register, kw('service-class'), 'Monitoring', kw(lease), 10.0], registered, _),
    ends_with_error(Conn, NameA, nobody_registered_this, 30, 'UNKNOWN', Ok1),
    ends_with_error(Conn, NameA, Mute, 1, 'TIMEOUT', Ok2),
    receive(Conn, Kept), param(Kept, content, Content),
    format("KEPT ~w~n", [Content]),
    command(Conn, [bye], bye, _),
    close(Stream),
    ( Ok1 == true, Ok2 == true -> halt(0) ; halt(1) ).

ends_with_error(Conn, Name, Receiver, Timeout, Tag, Ok) :-
    catch(( request(Conn, Name, Receiver, "(exec Player kick :playerNumber 9 :whichTeam our :power 10)",
                    Timeout, Answer),
            format("~w ANSWERED ~w~n", [Tag, Answer]), Ok = false ),
          Error,
          ( format("~w ~q~n", [Tag, Error]), Ok = true )).
