"""One module per group kind, each with the four functions of ``engine.kind.Kind``; ``engine.table`` lists them."""

__all__: list[str] = []
