// Module geo: see its headers.
