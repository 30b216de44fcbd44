#include <osgActor/io/ActorLexer>

namespace osgActor {

namespace {

bool endsWord(int c)
{
    return c == std::char_traits<char>::eof() || c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '{' ||
           c == '}' || c == ';' || c == '#' || c == '"';
}

} // namespace

int ActorLexer::get()
{
    const int c = _in.get();
    if (c == '\n') ++_line;
    return c;
}

Token ActorLexer::next()
{
    constexpr int eof = std::char_traits<char>::eof();
    // Skip blanks and comments, but not newlines: they end statements.
    for (;;)
    {
        const int c = peek();
        if (c == ' ' || c == '\t' || c == '\r') get();
        else if (c == '#')
        {
            while (peek() != '\n' && peek() != eof) get();
        }
        else break;
    }

    Token token;
    token.line = _line;
    const int c = get();
    if (c == eof)
    {
        token.type = TokenType::EndOfFile;
    }
    else if (c == '\n' || c == ';')
    {
        token.type = TokenType::EndOfStatement;
    }
    else if (c == '{')
    {
        token.type = TokenType::OpenBrace;
    }
    else if (c == '}')
    {
        token.type = TokenType::CloseBrace;
    }
    else if (c == '"')
    {
        token.type = TokenType::String;
        for (;;)
        {
            int s = get();
            if (s == '"') break;
            if (s == '\\' && (peek() == '"' || peek() == '\\')) s = get();
            if (s == '\n' || s == eof)
            {
                token.type = TokenType::Error;
                token.text = "the string that starts here is not closed on its line";
                break;
            }
            token.text.push_back(static_cast<char>(s));
        }
    }
    else
    {
        token.type = TokenType::Word;
        token.text.push_back(static_cast<char>(c));
        while (!endsWord(peek())) token.text.push_back(static_cast<char>(get()));
    }
    return token;
}

} // namespace osgActor
