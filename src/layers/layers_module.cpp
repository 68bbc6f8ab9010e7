// Module layers: see its headers.
