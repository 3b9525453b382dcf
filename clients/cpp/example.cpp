// A Common Framework agent in C++: the same program as the Java and Prolog clients.
//
//   cf_example HOST PORT NAME [TOKEN]
//
// It says hello, registers as a PlayerDecision, looks up a Kick provider, runs a fipa-request
// with it, then serves one fipa-request from any agent (ROS or TCP) and says bye.
#include <iostream>

#include "cf_gateway_client.hpp"

int main(int argc, char** argv) {
    if (argc < 4) {
        std::cerr << "usage: " << argv[0] << " HOST PORT NAME [TOKEN]\n";
        return 2;
    }
    try {
        cf::Gateway gw(argv[1], std::stoi(argv[2]), argv[3], argc > 4 ? argv[4] : "");
        std::cout << "CONNECTED " << gw.name << std::endl;
        gw.register_as("PlayerDecision", "blue", 9);
        std::cout << "REGISTERED" << std::endl;
        std::vector<std::string> providers = gw.lookup("Kick");
        std::cout << "PROVIDERS [";
        for (std::size_t i = 0; i < providers.size(); i++) std::cout << (i ? ", " : "") << providers[i];
        std::cout << "]" << std::endl;
        if (providers.empty()) return 1;
        cf::Value answer =
            gw.request(providers[0], "(exec Player kick :playerNumber 9 :whichTeam our :power 70 :direction 0.2)");
        std::cout << "ANSWER " << answer.head() << " " << cf::text_of(cf::param(answer, "content")) << std::endl;

        std::cout << "SERVING" << std::endl;
        cf::Value request = gw.receive();
        std::string content = cf::text_of(cf::param(request, "content"));
        // The content is the Framework Language: read it like any other S-expression.
        cf::Value action = cf::read(content);
        gw.reply(request, "agree");
        gw.reply(request, "inform", "(done-by-cpp " + action.head() + " " + std::to_string(content.size()) + ")");
        std::cout << "SERVED " << cf::text_of(cf::param(*cf::param(request, "sender"), "name")) << std::endl;
        gw.close();
    } catch (const std::exception& exc) {
        std::cerr << "cf_example: " << exc.what() << std::endl;
        return 1;
    }
    std::cout << "BYE" << std::endl;
    return 0;
}
