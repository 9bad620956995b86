// Side-by-side derivation speed of the lindenmayer npm package (1.5.4) on the classic systems that
// it can express, measured like tools/bench_derive: modules written over all steps / median time.
// Usage: node bench/lindenmayer_bench.js [CSV]   (after `npm install` in bench/)
'use strict';
const fs = require('fs');
const path = require('path');
const LSystem = require('lindenmayer');

const cases = [
  { grammar: 'grammars/classic/abop_1_24a.yaml', steps: 9, axiom: 'F', productions: { F: 'F[+F]F[-F]F' } },
  { grammar: 'grammars/classic/abop_1_24d.yaml', steps: 7, axiom: 'X', productions: { X: 'F[+X]F[-X]+X', F: 'FF' } },
  { grammar: 'grammars/classic/algae.yaml', steps: 30, axiom: 'A', productions: { A: 'AB', B: 'A' } },
  {
    grammar: 'grammars/classic/abop_1_31a.yaml', steps: 30, axiom: 'F1F1F1', ignoredSymbols: '+-F',
    productions: {
      '0<0>0': '0', '0<0>1': '1[+F1F1]', '0<1>0': '1', '0<1>1': '1',
      '1<0>0': '0', '1<0>1': '1F1', '1<1>0': '1', '1<1>1': '0', '+': '-', '-': '+',
    },
  },
];

function run(c) {
  const sys = new LSystem({ axiom: c.axiom, productions: c.productions, ignoredSymbols: c.ignoredSymbols || '' });
  let written = 0;
  const t0 = process.hrtime.bigint();
  for (let s = 0; s < c.steps; s++) written += sys.iterate(1).length;
  const t = Number(process.hrtime.bigint() - t0) / 1e9;
  return { t, written, final: sys.getString().length };
}

const csv = process.argv[2] || path.join('bench', 'results', 'derive_lindenmayer.csv');
const rows = ['grammar,engine,steps,final_modules,modules_written,median_s,modules_per_s'];
console.log('grammar'.padEnd(40), 'steps'.padStart(6), 'final modules'.padStart(14), 'median s'.padStart(10), 'Mmodules/s'.padStart(12));
for (const c of cases) {
  const repeats = c.steps >= 30 && c.ignoredSymbols ? 3 : 5;
  const times = [];
  let last;
  for (let r = 0; r < repeats + 1; r++) {
    last = run(c);
    if (r > 0) times.push(last.t);  // the first run warms the JIT
  }
  times.sort((a, b) => a - b);
  const med = times[Math.floor(times.length / 2)];
  const rate = last.written / med;
  console.log(c.grammar.padEnd(40), String(c.steps).padStart(6), String(last.final).padStart(14), med.toFixed(4).padStart(10), (rate / 1e6).toFixed(2).padStart(12));
  rows.push(`${c.grammar},lindenmayer-1.5.4,${c.steps},${last.final},${last.written},${med.toFixed(6)},${rate.toFixed(0)}`);
}
fs.writeFileSync(csv, rows.join('\n') + '\n');
console.log('wrote', csv);
