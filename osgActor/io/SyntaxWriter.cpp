#include <osgActor/io/SyntaxWriter>
#include <osgActor/text/Degrees>
#include <osgActor/text/Numbers>

namespace osgActor {

SyntaxWriter::SyntaxWriter(std::ostream& out, unsigned indent) : _out(out), _indent(indent)
{
    _text.reserve(kPiece + kPiece / 4);
}

SyntaxWriter::~SyntaxWriter() { flush(); }

SyntaxWriter& SyntaxWriter::begin(std::string_view keyword)
{
    if (!_blockOpen.empty()) openBlock();
    indent();
    _text += keyword;
    _blockOpen.push_back(false);
    return *this;
}

SyntaxWriter& SyntaxWriter::word(std::string_view text)
{
    _text += ' ';
    _text += text;
    flushIfLarge();
    return *this;
}

SyntaxWriter& SyntaxWriter::name(std::string_view name)
{
    if (needsQuotes(name)) return quoted(name);
    return word(name);
}

SyntaxWriter& SyntaxWriter::quoted(std::string_view text)
{
    _text += ' ';
    appendQuoted(_text, text);
    flushIfLarge();
    return *this;
}

SyntaxWriter& SyntaxWriter::number(double value)
{
    _text += ' ';
    appendNumber(_text, value);
    flushIfLarge();
    return *this;
}

SyntaxWriter& SyntaxWriter::angle(double radians)
{
    _text += ' ';
    appendAngle(_text, radians);
    flushIfLarge();
    return *this;
}

SyntaxWriter& SyntaxWriter::openBlock()
{
    if (!_blockOpen.back())
    {
        _text += " {\n";
        _blockOpen.back() = true;
    }
    return *this;
}

void SyntaxWriter::end()
{
    const bool hasBlock = _blockOpen.back();
    _blockOpen.pop_back();
    if (hasBlock)
    {
        indent();
        _text += '}';
    }
    _text += '\n';
    flushIfLarge();
}

void SyntaxWriter::write(const SyntaxStatement& statement)
{
    begin(statement.keyword);
    for (const SyntaxArgument& argument : statement.arguments)
    {
        if (argument.quoted) quoted(argument.text);
        else word(argument.text);
    }
    if (statement.hasBlock)
    {
        openBlock();
        write(statement.children);
    }
    end();
}

void SyntaxWriter::write(const std::vector<SyntaxStatement>& statements)
{
    for (const SyntaxStatement& statement : statements) write(statement);
}

void SyntaxWriter::flush()
{
    _out.write(_text.data(), static_cast<std::streamsize>(_text.size()));
    _text.clear();
}

void SyntaxWriter::indent() { _text.append(4 * (_indent + _blockOpen.size()), ' '); }

} // namespace osgActor
