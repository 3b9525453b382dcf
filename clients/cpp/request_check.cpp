// Checks how cf::Gateway::request ends when no answer comes, so that a test can see it from outside:
//
//   cf_request_check HOST PORT NAME MUTE
//
// First a request to a name nobody registered: the gateway's failure must end it ("UNKNOWN <why>").
// Then a request to MUTE, an agent that takes messages and never answers, with a 1 s timeout:
// it must end in time ("TIMEOUT <why>"). A message of another conversation that came meanwhile
// must still be there to receive ("KEPT <content>"). Exit 0 when all went as it should, else 1.
#include <iostream>

#include "cf_gateway_client.hpp"

static bool ends_with_error(cf::Gateway& gw, const std::string& receiver, double timeout, const std::string& tag) {
    try {
        cf::Value answer = gw.request(receiver, "(exec Player kick :playerNumber 9 :whichTeam our :power 10)", timeout);
        std::cout << tag << " ANSWERED " << answer.head() << std::endl;
        return false;
    } catch (const cf::GatewayError& exc) {
        std::cout << tag << " " << exc.what() << std::endl;
        return true;
    }
}

int main(int argc, char** argv) {
    if (argc < 5) {
        std::cerr << "usage: " << argv[0] << " HOST PORT NAME MUTE\n";
        return 2;
    }
    try {
        cf::Gateway gw(argv[1], std::stoi(argv[2]), argv[3]);
        gw.register_as("Monitoring", "", 0, 10.0);  // registered: others may send to it
        bool ok = ends_with_error(gw, "nobody_registered_this", 30.0, "UNKNOWN");
        ok = ends_with_error(gw, argv[4], 1.0, "TIMEOUT") && ok;
        cf::Value kept = gw.receive();
        std::cout << "KEPT " << cf::text_of(cf::param(kept, "content")) << std::endl;
        gw.close();
        return ok ? 0 : 1;
    } catch (const std::exception& exc) {
        std::cerr << "cf_request_check: " << exc.what() << std::endl;
        return 1;
    }
}
