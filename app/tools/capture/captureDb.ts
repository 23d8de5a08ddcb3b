/**
 * Captures kept in the browser's IndexedDB (database "maxl-captures", store "captures",
 * one record per capture by id) until the user deletes them. Records are stored as they
 * are: IndexedDB's structured clone keeps typed arrays.
 */
import type { CaptureRecord } from './protocol.ts';

const DB = 'maxl-captures';
const STORE = 'captures';

function open(): Promise<IDBDatabase> {
  return new Promise((resolve, reject) => {
    const req = indexedDB.open(DB, 1);
    req.onupgradeneeded = () => req.result.createObjectStore(STORE, { keyPath: 'id' });
    req.onsuccess = () => resolve(req.result);
    req.onerror = () => reject(req.error ?? new Error('IndexedDB would not open'));
  });
}

async function inStore<T>(mode: IDBTransactionMode, use: (store: IDBObjectStore) => IDBRequest<T>): Promise<T> {
  const db = await open();
  try {
    return await new Promise<T>((resolve, reject) => {
      const tx = db.transaction(STORE, mode);
      const req = use(tx.objectStore(STORE));
      tx.oncomplete = () => resolve(req.result);
      tx.onerror = () => reject(tx.error ?? req.error ?? new Error('IndexedDB transaction failed'));
      tx.onabort = () => reject(tx.error ?? new Error('IndexedDB transaction aborted (is the disk full?)'));
    });
  } finally {
    db.close();
  }
}

export function saveCapture(record: CaptureRecord): Promise<IDBValidKey> {
  return inStore('readwrite', (s) => s.put(record));
}

/** Every kept capture, newest first. */
export async function loadCaptures(): Promise<CaptureRecord[]> {
  const all = await inStore<CaptureRecord[]>('readonly', (s) => s.getAll());
  return all.sort((a, b) => (a.date < b.date ? 1 : -1));
}

export function deleteCapture(id: string): Promise<undefined> {
  return inStore('readwrite', (s) => s.delete(id));
}
