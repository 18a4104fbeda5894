#!/usr/bin/env python3
"""Operation counter for generated C/C++ functions (peer benchmark, not part of the build).

One counter for every variant (eomgen's headers and the SymPy-emitted ones), so the numbers
compare like for like. It finds the function FUNC in FILE, takes its body between the braces
and parses every statement of the forms

    [const] [TYPE] NAME = EXPR;        M(i, j) = EXPR;        x += EXPR;   (also -=, *=, /=)

with a small recursive-descent parser of C expressions, then counts:

  add   binary + and - (and the implied one of += / -=)
  mul   binary * (and *=), plus the multiplications of pow(x, k) with an integer literal k:
        k - 1 for k >= 2 (so pow(x, 2) is one multiplication, pow(x, 3) two), |k| - 1 and one
        division for k <= -1, nothing for k = 0 or 1
  div   binary / (and /=)
  neg   unary minus (unary + is free)
  call  calls of math functions (sin, cos, tan, sqrt, exp, log, atan2, pow with a non-integer
        exponent, ...); pow(x, 0.5) counts as one call (a sqrt)

Not counted: anything whose operands are all numeric literals (SymPy writes 1/2 as
(1.0/2.0), eomgen writes Scalar(0.5); the compiler folds both), casts Scalar(x) / double(x),
element accesses such as q(0), M(1, 0) or p.m, and plain copies (M(1, 0) = M(0, 1)).
Identifiers that are called but are not math functions are treated as element accesses.

Usage:
    count_ops.py FILE [--function mass_matrix_and_forcing] [--json]
prints "total add mul div neg call" (or a JSON object). Exit status 1 when the function is
missing or a statement cannot be parsed (with the offending text), 2 on usage errors.
"""

import argparse
import json
import re
import sys

MATH_FUNCS = {
    "sin", "cos", "tan", "asin", "acos", "atan", "atan2", "sinh", "cosh", "tanh", "sqrt",
    "cbrt", "exp", "log", "abs", "fabs", "pow", "hypot", "floor", "ceil", "fmod", "sign",
}
CAST_NAMES = {"Scalar", "double", "float", "static_cast<Scalar>", "static_cast<double>"}
TYPE_WORDS = {"const", "constexpr", "Scalar", "double", "float", "auto", "static", "int"}

TOKEN_RE = re.compile(
    r"\s*(?:(?P<num>(?:\d+\.\d*|\.\d+|\d+)(?:[eE][+-]?\d+)?[fFlL]?)"
    r"|(?P<id>[A-Za-z_][A-Za-z_0-9]*(?:::[A-Za-z_][A-Za-z_0-9]*)*)"
    r"|(?P<op>\+=|-=|\*=|/=|->|[-+*/(),.=;\[\]<>?:]))"
)


class ParseError(Exception):
    pass


class Counts:
    FIELDS = ("add", "mul", "div", "neg", "call")

    def __init__(self):
        for f in self.FIELDS:
            setattr(self, f, 0)

    def total(self):
        return sum(getattr(self, f) for f in self.FIELDS)

    def as_dict(self):
        d = {f: getattr(self, f) for f in self.FIELDS}
        d["total"] = self.total()
        return d


def tokenize(text):
    pos, out = 0, []
    text = text.rstrip()
    while pos < len(text):
        m = TOKEN_RE.match(text, pos)
        if not m or m.end() == pos:
            raise ParseError("cannot tokenize near: %r" % text[pos:pos + 40])
        kind = m.lastgroup
        out.append((kind, m.group(kind)))
        pos = m.end()
        while pos < len(text) and text[pos].isspace():
            pos += 1
    return out


class Expr:
    """Parsed expression node: ('lit', value) / ('var',) / ('op', name, children)."""
    __slots__ = ("kind", "value", "name", "kids")

    def __init__(self, kind, value=None, name=None, kids=()):
        self.kind, self.value, self.name, self.kids = kind, value, name, kids

    @property
    def is_lit(self):
        return self.kind == "lit"


def lit(v):
    return Expr("lit", value=v)


class Parser:
    def __init__(self, tokens):
        self.t, self.i = tokens, 0

    def peek(self, k=0):
        j = self.i + k
        return self.t[j] if j < len(self.t) else (None, None)

    def take(self, val=None):
        tok = self.peek()
        if tok[0] is None:
            raise ParseError("unexpected end of statement")
        if val is not None and tok[1] != val:
            raise ParseError("expected %r, found %r" % (val, tok[1]))
        self.i += 1
        return tok

    def expr(self):
        node = self.term()
        while self.peek()[1] in ("+", "-"):
            op = self.take()[1]
            rhs = self.term()
            node = self.binary("add", node, rhs, op)
        return node

    def term(self):
        node = self.unary()
        while self.peek()[1] in ("*", "/"):
            op = self.take()[1]
            rhs = self.unary()
            node = self.binary("mul" if op == "*" else "div", node, rhs, op)
        return node

    @staticmethod
    def binary(kind, a, b, op):
        if a.is_lit and b.is_lit:
            x, y = a.value, b.value
            v = {"+": lambda: x + y, "-": lambda: x - y, "*": lambda: x * y,
                 "/": lambda: x / y if y != 0 else float("nan")}[op]()
            return lit(v)
        return Expr("op", name=kind, kids=(a, b))

    def unary(self):
        tok = self.peek()
        if tok[1] == "-":
            self.take()
            a = self.unary()
            return lit(-a.value) if a.is_lit else Expr("op", name="neg", kids=(a,))
        if tok[1] == "+":
            self.take()
            return self.unary()
        return self.postfix()

    def postfix(self):
        kind, val = self.take()
        if kind == "num":
            node = lit(float(val.rstrip("fFlL")))
        elif val == "(":
            node = self.expr()
            self.take(")")
        elif kind == "id":
            name = val
            if name == "static_cast" and self.peek()[1] == "<":
                self.take("<")
                self.take()
                self.take(">")
                name = "Scalar"
            # member access p.m, x.y.z
            while self.peek()[1] == ".":
                self.take(".")
                self.take()
                name = None  # a member is a plain value
            if self.peek()[1] == "(":
                self.take("(")
                args = []
                if self.peek()[1] != ")":
                    args.append(self.expr())
                    while self.peek()[1] == ",":
                        self.take(",")
                        args.append(self.expr())
                self.take(")")
                base = name.split("::")[-1] if name else None
                if base in MATH_FUNCS:
                    node = Expr("op", name="call:" + base, kids=tuple(args))
                elif base in CAST_NAMES:
                    if len(args) != 1:
                        raise ParseError("cast with %d arguments" % len(args))
                    node = args[0]
                else:  # element access q(0), M(1, 0)
                    node = Expr("op", name="access", kids=tuple(args))
            else:
                node = Expr("var")
            while self.peek()[1] == "[":
                self.take("[")
                idx = self.expr()
                self.take("]")
                node = Expr("op", name="access", kids=(idx,))
        else:
            raise ParseError("unexpected token %r" % val)
        return node


def count_expr(node, c):
    if node.kind != "op":
        return
    name = node.name
    if name == "call:pow" and len(node.kids) == 2 and node.kids[1].is_lit:
        k = node.kids[1].value
        count_expr(node.kids[0], c)
        if float(k).is_integer():
            k = int(k)
            if k >= 2:
                c.mul += k - 1
            elif k <= -1:
                c.mul += -k - 1
                c.div += 1
            return
        c.call += 1
        return
    for kid in node.kids:
        count_expr(kid, c)
    if name == "add":
        c.add += 1
    elif name == "mul":
        c.mul += 1
    elif name == "div":
        c.div += 1
    elif name == "neg":
        c.neg += 1
    elif name.startswith("call:"):
        c.call += 1


def function_body(text, func):
    """The text between the braces of the first definition of func (name followed by '(')."""
    for m in re.finditer(r"\b%s\s*\(" % re.escape(func), text):
        # skip to the closing parenthesis of the parameter list
        i, depth = m.end() - 1, 0
        while i < len(text):
            if text[i] == "(":
                depth += 1
            elif text[i] == ")":
                depth -= 1
                if depth == 0:
                    break
            i += 1
        j = i + 1
        while j < len(text) and text[j] not in "{;":
            j += 1
        if j >= len(text) or text[j] != "{":
            continue  # a declaration or a call, not a definition
        depth, k = 0, j
        while k < len(text):
            if text[k] == "{":
                depth += 1
            elif text[k] == "}":
                depth -= 1
                if depth == 0:
                    return text[j + 1:k]
            k += 1
        raise ParseError("unbalanced braces in %s" % func)
    return None


def strip_comments(text):
    text = re.sub(r"/\*.*?\*/", " ", text, flags=re.S)
    return re.sub(r"//[^\n]*", " ", text)


def count_body(body):
    c = Counts()
    nstmt = 0
    for raw in body.split(";"):
        stmt = raw.strip()
        if not stmt or stmt.startswith("using ") or stmt.startswith("return") \
                or stmt.startswith("(void)") or stmt.startswith("#") \
                or stmt.startswith("static_assert") or stmt.startswith("eigen_assert"):
            continue  # declarations and the argument checks, no arithmetic of the function
        toks = tokenize(stmt)
        # find the assignment operator at depth 0
        depth, at = 0, None
        for idx, (kind, val) in enumerate(toks):
            if val in ("(", "["):
                depth += 1
            elif val in (")", "]"):
                depth -= 1
            elif depth == 0 and val in ("=", "+=", "-=", "*=", "/="):
                at = idx
                break
        if at is None:
            raise ParseError("not an assignment: %r" % stmt[:120])
        p = Parser(toks[at + 1:])
        try:
            node = p.expr()
            if p.i != len(p.t):
                raise ParseError("trailing tokens %r" % (p.t[p.i:p.i + 5],))
        except ParseError as e:
            raise ParseError("%s in statement %r" % (e, stmt[:200]))
        count_expr(node, c)
        op = toks[at][1]
        if op != "=" and not node.is_lit:
            setattr(c, {"+=": "add", "-=": "add", "*=": "mul", "/=": "div"}[op],
                    getattr(c, {"+=": "add", "-=": "add", "*=": "mul", "/=": "div"}[op]) + 1)
        nstmt += 1
    d = c.as_dict()
    d["statements"] = nstmt
    return d


def count_file(path, func="mass_matrix_and_forcing"):
    with open(path) as f:
        text = strip_comments(f.read())
    body = function_body(text, func)
    if body is None:
        raise ParseError("function %s not found in %s" % (func, path))
    return count_body(body)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("file")
    ap.add_argument("--function", default="mass_matrix_and_forcing")
    ap.add_argument("--json", action="store_true")
    a = ap.parse_args(argv)
    try:
        d = count_file(a.file, a.function)
    except (OSError, ParseError) as e:
        print("count_ops: error: %s" % e, file=sys.stderr)
        return 1
    if a.json:
        print(json.dumps(d))
    else:
        print("total %(total)d add %(add)d mul %(mul)d div %(div)d neg %(neg)d call %(call)d" % d)
    return 0


if __name__ == "__main__":
    sys.exit(main())
