// What the foxglove_js checks share: a decoder from a channel's schema (Foxglove's own OMG IDL
// parser and CDR deserializer, as the Foxglove app decodes), and a validator of decoded Foxglove
// messages against the message definitions in @foxglove/schemas.

import { parseIDL } from "@foxglove/omgidl-parser";
import { MessageReader } from "@foxglove/omgidl-serialization";
import internal from "@foxglove/schemas/internal.js";

const { foxgloveMessageSchemas } = internal;  // CommonJS: no named export for ESM

export function makeDecoder(schemaName, schemaText) {
  return new MessageReader(schemaName, parseIDL(schemaText));
}

const primitiveCheck = {
  float64: (v) => typeof v === "number",
  uint32: (v) => Number.isInteger(v) && v >= 0 && v <= 0xffffffff,
  int32: (v) => Number.isInteger(v),
  boolean: (v) => typeof v === "boolean",
  string: (v) => typeof v === "string",
  bytes: (v) => v instanceof Uint8Array,
};

function checkValue(value, type, path, errors) {
  if (type.type === "primitive") {
    const ok = primitiveCheck[type.name];
    if (!ok) errors.push(`${path}: no check for primitive ${type.name}`);
    else if (!ok(value)) errors.push(`${path}: ${JSON.stringify(value)?.slice(0, 40)} is not a ${type.name}`);
  } else if (type.type === "enum") {
    if (!type.enum.values.some((e) => e.value === value)) errors.push(`${path}: ${value} is not a ${type.enum.name}`);
  } else if (type.type === "nested") {
    checkMessage(value, type.schema, path, errors);
  } else {
    errors.push(`${path}: unknown field type ${type.type}`);
  }
}

function checkMessage(value, schema, path, errors) {
  if (value === null || typeof value !== "object") {
    errors.push(`${path}: not a ${schema.name} object`);
    return;
  }
  const known = new Set(schema.fields.map((f) => f.name));
  for (const key of Object.keys(value)) {
    if (!known.has(key)) errors.push(`${path}.${key}: not a field of ${schema.name}`);
  }
  for (const field of schema.fields) {
    const v = value[field.name];
    const at = `${path}.${field.name}`;
    if (v === undefined) {
      if (!field.optional) errors.push(`${at}: missing (required by ${schema.name})`);
      continue;
    }
    if (field.array) {
      if (!Array.isArray(v)) errors.push(`${at}: not an array`);
      else v.forEach((item, i) => checkValue(item, field.type, `${at}[${i}]`, errors));
    } else {
      checkValue(v, field.type, at, errors);
    }
  }
}

// Errors (empty when valid) of a decoded message against @foxglove/schemas' definition of
// `schemaName` ("foxglove::ImageAnnotations" or "foxglove.ImageAnnotations").
export function validateFoxglove(value, schemaName) {
  const name = schemaName.replace(/^foxglove(::|\.)/, "");
  const schema = foxgloveMessageSchemas[name];
  if (!schema) return [`${schemaName}: not in @foxglove/schemas`];
  const errors = [];
  checkMessage(value, schema, name, errors);
  return errors;
}

// Checks the IDL text a channel carries against @foxglove/schemas: every required field of every
// struct, in the definition's order (the order CDR encodes them in).
export function idlFieldsMatch(schemaName, schemaText) {
  const errors = [];
  const definitions = parseIDL(schemaText);
  const byName = new Map(definitions.map((d) => [d.name, d]));
  const visit = (schema) => {
    const idl = byName.get(`foxglove::${schema.name === "Timestamp" ? "Time" : schema.name}`);
    if (!idl) {
      errors.push(`${schema.name}: not defined in the channel's IDL`);
      return;
    }
    const required = schema.fields.filter((f) => !f.optional).map((f) => f.name);
    const got = idl.definitions.map((d) => d.name);
    if (JSON.stringify(required) !== JSON.stringify(got)) errors.push(`${schema.name}: fields ${got} != ${required}`);
    for (const f of schema.fields) if (f.type.type === "nested" && !f.optional) visit(f.type.schema);
  };
  visit(foxgloveMessageSchemas[schemaName.replace(/^foxglove::/, "")]);
  return errors;
}

// A checker that counts passes and prints failures.
export function makeChecker() {
  const state = { passed: 0, failed: 0 };
  state.check = (condition, what) => {
    if (condition) state.passed++;
    else {
      state.failed++;
      if (state.failed <= 30) console.error(`FAIL: ${what}`);
    }
  };
  return state;
}
